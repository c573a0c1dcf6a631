"""Every public callable refuses bad input (issue 21).

Each public callable of every subpackage (found through the ``__all__`` of each package *and*
each module, so that a new function cannot escape) has one valid example call in
:data:`REGISTRY`. The test first checks that the valid call succeeds with a finite result, then
mutates one argument at a time according to the argument's declared kind:

* arrays: NaN, +inf, empty, one dimension more, one dimension less, a string instead of the array,
  and (for arrays paired with another argument) a length that no longer matches;
* covariances: additionally non-symmetric, indefinite, negative-definite and singular matrices
  (semidefinite arguments: all but singular);
* scalars: zero, negative, NaN, inf, out of range, a string; counts: zero, negative, a fraction;
* options: an unknown string; generators and callables: a string.

Every mutated call must raise ``ValueError`` or ``TypeError`` whose message names the argument;
any other exception, a silent success or a non-finite result fails. The degenerate but valid inputs
(one sensor, identical readings, omega at the ends, a stationary target, a target on a sensor,
extreme scales) are tested at the end.
"""

from __future__ import annotations

import dataclasses
import functools
import importlib
import inspect
import pkgutil
import typing
import re
from collections.abc import Callable
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import fusion
from fusion.optimise.swarm import SwarmOptions

# --------------------------------------------------------------------------------------------
# enumeration of the public callables
# --------------------------------------------------------------------------------------------


def public_callables() -> dict[str, Callable[..., Any]]:
    """Every callable named in the ``__all__`` of a package or module of :mod:`fusion` (a new dict on each call)."""
    return dict(_public_callables())


@functools.lru_cache(maxsize=1)
def _public_callables() -> dict[str, Callable[..., Any]]:
    """:func:`public_callables`, enumerated once per process (five registries ask for it at collection)."""
    out: dict[str, Callable[..., Any]] = {}
    names = ["fusion"] + [m.name for m in pkgutil.walk_packages(fusion.__path__, "fusion.")]
    for modname in names:
        mod = importlib.import_module(modname)
        for n in getattr(mod, "__all__", []):
            obj = getattr(mod, n)
            if callable(obj) and typing.get_origin(obj) is None:  # type aliases (GlueValues, ...) are not callables
                key = f"{obj.__module__}.{obj.__qualname__}"
                out[key] = obj
    return out


# --------------------------------------------------------------------------------------------
# argument kinds and their mutations
# --------------------------------------------------------------------------------------------

ARR = ("nan", "inf", "empty", "more", "less", "str")
COV = ARR + ("nonsym", "indef", "negdef", "sing")
PSD = ARR + ("nonsym", "indef", "negdef")
POS = ("zero", "neg", "nan_s", "inf_s", "str")
NONNEG = ("neg", "nan_s", "inf_s", "str")
REAL = ("nan_s", "inf_s", "str")
UNIT = ("below", "above", "nan_s", "str")
COUNT = ("zero", "neg", "frac", "str")
OPT = ("unknown",)
BATCH = ("nan", "inf", "empty", "less", "str")  # arrays with documented leading batch axes
ZARR = ("nan", "inf", "empty", "less", "str", "len")  # (n,) or (n, runs)
OBJ = ("str",)


@dataclasses.dataclass
class A:
    """One argument of a valid call: its value and the mutations that must be refused.

    A mutation is a kind named in this module (``"nan"``, ``"str"``, ...) or an explicit ``(label, bad value)`` pair
    for what no kind describes (another scenario's study, a table without a column, ...).
    """

    value: Any
    mutations: tuple[str | tuple[str, Any], ...] = ()


def _arr(x: Any) -> np.ndarray:
    return np.array(x, dtype=float, copy=True)


def _eig_mut(P: np.ndarray, how: str) -> np.ndarray | None:
    if P.ndim < 2:
        return None
    w, V = np.linalg.eigh(0.5 * (P + np.swapaxes(P, -1, -2)))
    w = w.copy()
    if how == "indef":
        if P.shape[-1] < 2:
            return None
        w[..., 0] = -w[..., -1]
    elif how == "negdef":
        w = -w
    elif how == "sing":
        w[..., 0] = 0.0
    return np.einsum("...ij,...j,...kj->...ik", V, w, V)


def mutate(value: Any, how: str) -> Any:
    """Apply one mutation; ``None`` when it does not apply to this value."""
    if isinstance(value, list) and value and isinstance(value[0], np.ndarray) and how not in ("len", "str"):
        inner = mutate(value[0], how)
        return None if inner is None else [inner] + value[1:]
    if how == "str":
        return "abc"
    if how == "unknown":
        return "no-such-option"
    if how == "notstr":
        return 3.0
    scalar = {"zero": 0.0, "neg": -1.0, "nan_s": float("nan"), "inf_s": float("inf"), "below": -0.1,
              "above": 1.1, "frac": 2.5}
    if how in scalar:
        if how in ("zero", "neg") and isinstance(value, (int, np.integer)):
            return int(scalar[how])
        return scalar[how]
    if isinstance(value, list):
        if how == "len":
            return value[:-1]
        return None
    x = _arr(value)
    if how == "nan":
        x.flat[0] = np.nan
        return x
    if how == "inf":
        x.flat[-1] = np.inf
        return x
    if how == "empty":
        return np.empty((0,) + x.shape[1:])
    if how == "more":
        return np.repeat(x[..., None], 2, axis=-1)
    if how == "less":
        return x[0] if x.ndim >= 1 else None
    if how == "len":
        return x[:-1]
    if how == "lensq":
        return x[:-1, :-1]
    if how == "nonsym":
        if x.shape[-1] < 2:
            return None
        s = np.max(np.abs(x))
        x[..., 0, -1] += 0.5 * s
        return x
    if how in ("indef", "negdef", "sing"):
        return _eig_mut(x, how)
    raise AssertionError(how)


# --------------------------------------------------------------------------------------------
# valid example calls
# --------------------------------------------------------------------------------------------


def rng() -> np.random.Generator:
    return np.random.default_rng(0)


@functools.cache
def _objects() -> dict[str, Any]:
    from fusion.estimates.mixtures import GaussianMixture
    from fusion.filtering.kalman import cv_model, gain_sequence
    from fusion.filtering.tracks import local_track
    from fusion.scenarios import infrared_radar, range_bearing, two_sensor

    model = cv_model(1.0)
    F, H = model.F, model.H
    Q = np.diag([0.0, 1.0, 0.0, 1.0])
    R = np.eye(2)
    P0 = np.eye(4) * 10.0
    gains = gain_sequence(F, H, Q, R, P0, 5)
    z = np.random.default_rng(1).normal(size=(3, 5, 2))
    x0 = np.zeros((3, 4))
    ta = local_track(z, F, H, Q, R, x0, 0.5 * P0, 0.5 * P0)
    tb = local_track(z + 0.1, F, H, Q, 2 * R, x0, 0.5 * P0, 0.5 * P0)
    gA = GaussianMixture(np.array([0.4, 0.6]), np.array([[0.0, 0.0], [1.0, 1.0]]),
                         np.stack([np.eye(2), 2 * np.eye(2)]))
    gB = GaussianMixture(np.array([1.0]), np.array([[0.5, 0.0]]), np.eye(2)[None] * 1.5)
    sim = infrared_radar.simulate(np.random.default_rng(2), runs=2, duration=0.5)
    ct = infrared_radar.cartesian_tracks(sim)
    sc = range_bearing.RangeBearingScenario(frames=2, n_particles=60, n_samples=60, n_central=100,
                                            em_iterations=2, n_components=1)
    runs_rb = range_bearing.monte_carlo(sc, 1, 1, all_nodes_first=False)
    sc2 = two_sensor.two_sensor_scenario(np.eye(2) * 2500.0, np.eye(2) * 2500.0, np.diag([0.0, 1.0, 0.0, 1.0]),
                                         np.random.default_rng(11), runs=2)
    return dict(F=F, Q=Q, H=H, R=R, P0=P0, gains=gains, z=z, x0=x0, ta=ta, tb=tb, gA=gA, gB=gB,
                sim=sim, ct=ct, sc=sc, runs_rb=runs_rb, sc2=sc2)


X5 = np.array([10.1, 10.3, 9.9, 10.0, 12.0])
XT = np.random.default_rng(3).normal(10.0, 1.0, size=(8, 4))  # (epochs, sensors)
P1 = np.array([[2.0, 0.3], [0.3, 1.0]])
P2 = np.array([[1.0, -0.2], [-0.2, 3.0]])
v1 = np.array([0.0, 1.0])
v2 = np.array([0.5, 0.8])
C3 = np.array([[1.0, 0.8, 0.1], [0.8, 1.0, 0.2], [0.1, 0.2, 1.0]])
T_REG = np.arange(0.0, 2.0, 0.1)
Z_REG = 3.0 + 2.0 * T_REG
TQ = np.array([0.55, 1.25])
HR = np.array([[1.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, -1.0]])
RR = np.diag([1.0, 2.0, 1.5, 1.0]) + 0.2
ZR = np.array([1.0, 2.0, 3.1, -0.9])


def _quad(w: float) -> float:
    return (w - 0.3) ** 2


def _quad_vec(e: np.ndarray) -> np.ndarray:
    e = np.asarray(e)
    return np.sum((e - 0.5) ** 2, axis=-1)


def _quad_batch(active: np.ndarray, e: np.ndarray) -> np.ndarray:
    return _quad_vec(e)


@dataclasses.dataclass
class _Loglik:
    """A log-likelihood callable returning fixed values (mutated by the ``ll_*`` mutations)."""

    values: np.ndarray

    def __call__(self, x: np.ndarray) -> np.ndarray:
        return self.values


def _linear_register(z: np.ndarray) -> np.ndarray:
    return 0.5 * (z[:-1] + z[1:])


def registry() -> dict[str, dict[str, A]]:
    """Valid example calls: callable name -> its arguments, each with the mutations to refuse."""
    o = _objects()
    gA, gB = o["gA"], o["gB"]
    R: dict[str, dict[str, A]] = {}
    rs = "fusion.readings.fusion_set."
    R[rs + "arithmetic_mean"] = dict(x=A(X5, ARR))
    R[rs + "optimal_fusion_set"] = dict(x=A(X5, ARR), scale=A(2.0, POS), threshold=A("mean", OPT))
    R[rs + "support_degree"] = dict(x=A(X5, ARR), alpha=A(0.25, POS))
    R[rs + "fusion_set_weights"] = dict(x=A(X5, ARR), scale=A(2.0, POS))
    R[rs + "fuse_epochs"] = dict(x=A(XT, ("nan", "inf", "empty", "more", "str")), method=A("optimal_fusion_set", OPT))
    R[rs + "distance_matrix"] = dict(x=A(X5, ARR))
    R[rs + "mean_distances"] = dict(x=A(X5, ARR), threshold=A("mean", OPT))
    R[rs + "optimal_set_members"] = dict(x=A(X5, ARR), threshold=A("mean", OPT))
    R[rs + "fusion_degree_matrix"] = dict(x=A(X5, ARR), scale=A(2.0, POS))
    R[rs + "consistency_degree"] = dict(C=A(C3, ARR))
    R[rs + "distribution_balance"] = dict(C=A(C3, ARR), form=A("left", OPT))
    R[rs + "belief_matrix"] = dict(x=A(X5, ARR), scale=A(1.0, POS), limit=A(2.0, NONNEG))
    R[rs + "perron_weights"] = dict(B=A(C3, ARR))
    R[rs + "belief_degree"] = dict(x=A(X5, ARR), scale=A(1.0, POS), limit=A(2.0, NONNEG))
    R[rs + "binary_deletion"] = dict(x=A(X5, ARR), eps=A(1.0, POS), min_support=A(0.5, ("zero", "neg", "nan_s", "str")))
    R["fusion.readings.robust.robust_fuse"] = dict(x=A(XT, ("nan", "inf", "empty", "more", "str")), method=A("biweight", OPT),
                                                   c_biweight=A(4.685, POS))
    rw = "fusion.readings.weighting."
    R[rw + "optimal_weights"] = dict(variances=A([1.0, 2.0, 4.0], ARR))
    R[rw + "minimum_variance"] = dict(variances=A([1.0, 2.0, 4.0], ARR))
    R[rw + "inverse_variance_weights"] = dict(estimates=A(np.array([[1.0, 2.0], [1.5, 0.5]]), ("nan", "inf", "empty", "str")), floor=A(1e-12, POS))
    R[rw + "running_variances"] = dict(X=A(XT, BATCH), estimator=A("lecture", OPT))
    R[rw + "running_means"] = dict(X=A(XT, BATCH))
    R[rw + "awf"] = dict(X=A(XT, BATCH), variance=A("lecture", OPT))
    R[rw + "learned_variances"] = dict(Y=A(XT, BATCH))
    R[rw + "corrected_variances"] = dict(learned=A(np.array([[1.0, 2.0, 1.5, 0.7]] * 3), ("nan", "inf", "empty", "more", "str")))
    R[rw + "ls_learning"] = dict(Y=A(XT, BATCH))
    R[rw + "running_average"] = dict(Z=A(XT, ("nan", "inf", "empty", "str")), memory=A("forgetting", OPT),
                                     forgetting=A(0.9, UNIT), window=A(3, COUNT), axis=A(0, ("str", "big")))
    R[rw + "tracking_variances"] = dict(X=A(XT, BATCH), estimator=A("sample", OPT), memory=A("window", OPT),
                                        forgetting=A(0.9, UNIT), window=A(3, COUNT))
    R[rw + "fuse_current"] = dict(X=A(XT, BATCH), variances=A(np.array([1.0, 2.0, 3.0, 4.0]), ("nan", "inf", "empty", "str")),
                                  guard=A("abs", OPT))
    R[rw + "variance_estimates"] = dict(X=A(XT, BATCH), estimator=A("centred", OPT))
    R[rw + "difference_variances"] = dict(X=A(XT, BATCH), memory=A("forgetting", OPT), forgetting=A(0.9, UNIT),
                                          window=A(3, COUNT))
    R[rw + "cumulative_fusion"] = dict(X=A(XT, BATCH), variances=A(np.array([1.0, 2.0, 3.0, 4.0]), ("nan", "inf", "empty", "str")),
                                       guard=A("abs", OPT), time_weights=A("precision", OPT))
    R[rw + "learned_fused_variance"] = dict(variances=A(np.array([1.0, 2.0, 4.0]), BATCH + ("neg_entry",)))
    R[rw + "wls"] = dict(H=A(np.ones(4), ("nan", "inf", "empty", "more", "str", "len")),
                         W=A(np.diag([1.0, 2.0, 3.0, 4.0]), ("nan", "inf", "empty", "more", "str", "nonsym", "indef", "negdef")),
                         Y=A(np.array([1.0, 1.2, 0.9, 1.1]), ARR + ("len",)))
    rc = "fusion.readings.consistency."
    R[rc + "consistency_mask"] = dict(x=A(X5, ("nan", "inf", "empty", "str")), eps=A(0.5, ("neg", "nan_s", "str")),
                                    adjacent=A("sorted", ("unknown",)))
    R[rc + "consistency_awf"] = dict(X=A(XT, BATCH), eps=A(3.0, ("neg", "nan_s", "str")), variance=A("lecture", OPT),
                                     guard=A("abs", OPT))
    rb = "fusion.readings.biased."
    Hb = np.array([[1.0, 0.5], [0.2, 1.0], [1.0, 1.0]])
    yb = np.array([1.0, 2.0, 2.5])
    R[rb + "least_squares"] = dict(H=A(Hb, ARR), y=A(yb, ARR + ("len",)))
    R[rb + "ridge"] = dict(H=A(Hb, ARR), y=A(yb, ARR + ("len",)), k=A(0.1, NONNEG))
    blocks = dict(Hs=A([Hb, Hb], ARR + ("len",)), Rs=A([np.eye(3), 2 * np.eye(3)], COV),
                  ys=A([yb, yb + 0.1], ARR + ("len",)), k=A(0.1, NONNEG))
    R[rb + "ridge_centralised"] = blocks
    R[rb + "ridge_distributed"] = dict(blocks)
    R[rb + "scalar_ridge_moments"] = dict(m=A(5, COUNT), sigma=A(1.0, POS), x=A(np.array([1.0, 2.0, 3.0]), ("nan", "inf", "str")),
                                          k=A(np.array([0.1, 0.5, 1.0]), ("nan", "inf", "str", "len", "neg_entry")))
    R[rb + "optimal_ridge_k"] = dict(sigma=A(1.0, POS), x=A(2.0, REAL))
    R[rb + "reliability"] = dict(bias=A(np.array([0.1, 0.2, 0.0]), ("nan", "inf", "str")),
                                 sd=A(np.array([1.0, 0.5, 2.0]), ("nan", "inf", "str", "len", "neg_entry")),
                                 delta=A(1.0, POS))
    R[rb + "plugin_ridge"] = dict(H=A(Hb, ARR), y=A(yb, ZARR), sigma=A(1.0, POS))
    R[rb + "ridge_fusion_plugin"] = dict(Hs=A([Hb, Hb], ARR + ("len",)), Rs=A([np.eye(3), 2 * np.eye(3)], COV),
                                         ys=A([yb, yb + 0.1], ZARR), where=A("distributed", OPT))
    R[rb + "plugin_risk"] = dict(theta=A(np.array([0.0, 1.0, 3.0]), ("nan", "inf", "str")), c=A(1.0, POS),
                                 m=A(5, COUNT), nodes=A(40, COUNT))
    R[rb + "plugin_crossings"] = dict(c=A(1.0, POS), m=A(5, COUNT), upper=A(8.0, ("nan_s", "str")))
    Ab = np.array([[2.0, 0.3], [0.3, 0.5]])
    R[rb + "ridge_risk"] = dict(A=A(Ab, COV), x=A(np.array([1.0, -2.0]), ARR), k=A(np.array([0.0, 0.1]), ("nan", "inf", "str", "neg_entry")))
    R[rb + "best_ridge_k"] = dict(A=A(Ab, COV), x=A(np.array([1.0, -2.0]), ARR))
    R[rb + "james_stein"] = dict(y=A(np.array([1.0, 2.0, -1.0, 0.5]), ("nan", "inf", "empty", "less", "str")), sigma=A(1.0, POS))
    rr = "fusion.readings.correlated."
    R[rr + "gls"] = dict(H=A(HR, ARR), R=A(RR, COV + ("lensq",)), z=A(ZR, ZARR))
    R[rr + "ldl_recurrences"] = dict(R=A(RR, COV))
    R[rr + "lagrange_weights"] = dict(H=A(HR, ARR), R=A(RR, COV + ("lensq",)))
    R[rr + "gauss_markov_gap"] = dict(H=A(HR, ARR), R=A(RR, COV + ("lensq",)), rng=A(rng(), OBJ), draws=A(5, COUNT))
    R[rr + "ldl_unpivoted"] = dict(R=A(RR, COV))
    R[rr + "unit_lower_inverse"] = dict(L=A(np.array([[1.0, 0.0], [0.5, 1.0]]), ("nan", "inf", "empty", "more", "less", "str")))
    R[rr + "pseudo_measurement_fusion"] = dict(H=A(HR, ARR), R=A(RR, COV + ("lensq",)), z=A(ZR, ZARR))
    R[rr + "naive_fusion"] = dict(H=A(HR, ARR), R=A(RR, COV + ("lensq",)), z=A(ZR, ZARR), block=A(2, COUNT))
    R[rr + "eigen_decorrelation_fusion"] = dict(H=A(HR, ARR), R=A(RR, COV + ("lensq",)), z=A(ZR, ZARR))
    R[rr + "gls_weights"] = dict(H=A(HR, ARR), R=A(RR, COV + ("lensq",)))
    R6 = np.kron(np.diag([1.0, 4.0, 9.0]) + 2.25, np.eye(2)) + 0.1 * np.kron(np.eye(3), np.array([[0.0, 1.0], [1.0, 0.0]]))
    R[rr + "scalar_lagrange_weights"] = dict(R=A(R6, COV), d=A(2, COUNT))
    H6 = np.kron(np.ones((3, 1)), np.eye(2))
    R[rr + "gls_low_rank"] = dict(H=A(H6, ARR), D=A(np.repeat([1.0, 4.0, 9.0], 2), ("nan", "inf", "empty", "more", "less", "str", "len", "neg_entry")),
                                  U=A(1.5 * H6, ("nan", "inf", "empty", "more", "str", "len")),
                                  z=A(np.array([1.0, 2.0, 0.5, 1.5, 1.2, 1.9]), ZARR))
    R[rr + "low_rank_count"] = dict(N=A(600, COUNT), d=A(2, COUNT), r=A(2, COUNT))
    rv = "fusion.readings.wavelet."
    sig = np.sin(np.linspace(0, 6, 64)) + 0.1 * np.random.default_rng(4).normal(size=64)
    R[rv + "denoise"] = dict(x=A(sig, ("nan", "inf", "empty", "less", "str")), wavelet=A("db4", OPT), level=A(2, COUNT), mode=A("soft", OPT),
                            threshold=A("bayes", OPT), transform=A("swt", OPT))
    R[rv + "reconstruct"] = dict(X=A(np.stack([sig + 3, sig + 3.05, sig + 2.98]), ARR), wavelet=A("db4", OPT),
                                 level=A(2, COUNT), normaliser=A("max", OPT), mode=A("soft", OPT),
                                 threshold=A("universal", OPT), order=A("fuse-first", OPT),
                                 variance=A("window", OPT), window=A(8, COUNT), transform=A("swt", OPT))
    Xv = np.stack([sig + 3, sig + 3.05, sig + 2.98])
    R[rv + "variance_estimates"] = dict(X=A(Xv, ARR), Y=A(Xv - 0.01, ("nan", "inf", "empty", "more", "less", "str")),
                                        norms=A(np.array([4.0, 4.1, 3.9]), ("nan", "inf", "empty", "more", "str", "len", "neg_entry")),
                                        variance=A("running", OPT), window=A(8, COUNT))
    # a residual that is not constant (X - 0.01 alone has zero variance: refused by every residual reading, fuzz 37a D3)
    Yv = Xv - 0.01 - 0.005 * np.random.default_rng(5).normal(size=Xv.shape)
    R[rv + "fuse_denoised"] = dict(X=A(Xv, ARR), Y=A(Yv, ("nan", "inf", "empty", "more", "less", "str")),
                                   normaliser=A("max-raw", OPT), variance=A("running", OPT), window=A(8, COUNT))
    ec = "fusion.estimates.ci."
    R[ec + "covariance_intersection"] = dict(x1=A(v1, ARR + ("len",)), P1=A(P1, COV), x2=A(v2, ARR + ("len",)),
                                             P2=A(P2, COV), omega=A(0.4, UNIT), criterion=A("trace", OPT))
    R[ec + "ci_weight"] = dict(P1=A(P1, COV + ("lensq",)), P2=A(P2, COV), criterion=A("det", OPT))
    R[ec + "ci_objective"] = dict(omega=A(0.4, UNIT), P1=A(P1, COV + ("lensq",)), P2=A(P2, COV),
                                  criterion=A("trace", OPT))
    R[ec + "convex_combination"] = dict(x1=A(v1, ARR + ("len",)), P1=A(P1, COV), x2=A(v2, ARR), P2=A(P2, COV))
    R[ec + "split_covariance_intersection"] = dict(
        x1=A(v1, ARR + ("len",)), P1d=A(P1, PSD), P1i=A(0.5 * P1, PSD), x2=A(v2, ARR), P2d=A(P2, PSD),
        P2i=A(0.5 * P2, PSD), omega=A(0.5, UNIT), criterion=A("trace", OPT))
    R[ec + "split_ci_objective"] = dict(omega=A(0.4, UNIT), P1d=A(P1, PSD), P1i=A(0.5 * P1, PSD), P2d=A(P2, PSD),
                                        P2i=A(0.5 * P2, PSD))
    R["fusion.data.as_printed.wang2024_eqs_1_2"] = dict(x1=A(v1, ARR + ("len",)), P1=A(P1, COV), x2=A(v2, ARR),
                                                        P2=A(P2, COV), omega=A(0.4, UNIT))
    R["fusion.estimates.fuzzy_cluster.fuzzy_cluster_fusion"] = dict(
        xs=A(np.array([[0.0, 1.0], [0.1, 1.1], [3.0, 3.0]]), ARR + ("len",)),
        Ps=A(np.stack([P1, P2, P1]), COV), level=A(0.01, UNIT))
    em = "fusion.estimates.mixtures."
    R[em + "GaussianMixture"] = dict(weights=A(np.array([0.4, 0.6]), ARR + ("len",)),
                                     means=A(np.array([[0.0, 0.0], [1.0, 1.0]]), ARR),
                                     covs=A(np.stack([P1, P2]), COV))
    R[em + "logsumexp"] = dict(a=A(np.array([[0.0, -1.0], [2.0, 1.0]]), ("nan", "empty", "str")), axis=A(0, ()))
    R[em + "gaussian_logpdf"] = dict(x=A(np.array([[0.0, 1.0], [1.0, 2.0]]), ("nan", "inf", "empty", "str", "more")),
                                     mean=A(v1, ARR + ("len",)), cov=A(P1, COV))
    R[em + "gm_logpdf"] = dict(gm=A(gA, OBJ), x=A(np.array([[0.0, 1.0], [1.0, 2.0]]), ("nan", "inf", "empty", "str", "more", "lencol")))
    R[em + "gm_moments"] = dict(gm=A(gA, OBJ))
    R[em + "gm_sample"] = dict(gm=A(gA, OBJ), rng=A(rng(), OBJ), n=A(10, COUNT))
    xe = np.random.default_rng(5).normal(size=(40, 2))
    R[em + "weighted_em"] = dict(x=A(xe, ARR), w=A(np.full(40, 1 / 40), ARR + ("len",)), n_components=A(2, COUNT),
                                 rng=A(rng(), OBJ), max_iter=A(5, COUNT), tol=A(1e-8, NONNEG), floor=A(1e-6, NONNEG))
    xb = np.random.default_rng(5).normal(size=(2, 40, 2))
    R[em + "weighted_em_batch"] = dict(x=A(xb, ARR), w=A(np.full((2, 40), 1 / 40), ("nan", "inf", "str", "len", "less")),
                                       n_components=A(2, COUNT), rngs=A([rng(), rng()], ("str", "len")),
                                       max_iter=A(5, COUNT), tol=A(1e-8, NONNEG), floor=A(1e-6, NONNEG))
    ch = "fusion.estimates.chernoff."
    sx = "fusion.optimise.simplex."
    means = np.array([v1, v2])
    covs = np.stack([P1, P2])
    R[sx + "check_simplex"] = dict(eps=A(np.array([0.3, 0.7]), ARR + ("len",)), n=A(2, COUNT))
    R[ch + "chernoff_fuse_gaussians"] = dict(means=A(means, ARR + ("len",)), covs=A(covs, COV),
                                             eps=A(np.array([0.3, 0.7]), ARR + ("len",)))
    R[ch + "gaussian_log_normaliser"] = dict(means=A(means, ARR + ("len",)), covs=A(covs, COV),
                                             eps=A(np.array([0.3, 0.7]), ARR + ("len",)))
    R[ch + "is_second_moment"] = dict(means=A(means, ARR + ("len",)), covs=A(covs, COV),
                                      eps=A(np.array([0.3, 0.7]), ARR + ("len",)),
                                      eps0=A(np.array([0.5, 0.5]), ARR + ("len",)))
    R[ch + "gaussian_chernoff_weights"] = dict(means=A(means, ARR + ("len",)), covs=A(covs, COV))
    R[ch + "covariance_intersection_weights"] = dict(covs=A(covs, COV), criterion=A("det", OPT))
    R[ch + "gaussian_kl"] = dict(m0=A(v1, ARR + ("len",)), P0=A(P1, COV), m1=A(v2, ARR), P1=A(P2, COV))
    R[ch + "log_normaliser_two_gaussians"] = dict(a=A(v1, ARR + ("len",)), A=A(P1, COV), b=A(v2, ARR), B=A(P2, COV),
                                                  omega=A(0.4, UNIT))
    R[ch + "first_order_fusion"] = dict(gms=A([gA, gB], OBJ), eps=A(np.array([0.4, 0.6]), ARR + ("len",)))
    xr = np.random.default_rng(6).normal(size=(30, 2))
    R[ch + "log_densities"] = dict(gms=A([gA, gB], OBJ), x=A(xr, ("nan", "inf", "empty", "more", "str", "lencol")))
    from fusion.estimates.chernoff import log_densities
    L = log_densities([gA, gB], xr)
    lg = L.mean(axis=1)
    R[ch + "is_objective"] = dict(L=A(L, ARR), log_g=A(lg, ARR + ("len",)),
                                  eps=A(np.array([0.4, 0.6]), ("nan", "inf", "empty", "less", "str", "len")))
    R[ch + "fused_weights"] = dict(L=A(L, ARR), log_g=A(lg, ARR + ("len",)), eps=A(np.array([0.4, 0.6]), ARR + ("len",)))
    R[sx + "minimise_on_simplex"] = dict(f=A(_quad_vec, OBJ), n=A(2, COUNT))
    R[ch + "simplex_minimum"] = dict(L=A(L, ARR), log_g=A(lg, ARR + ("len",)))
    R[ch + "fuse_mixtures"] = dict(gms=A([gA, gB], OBJ), rng=A(rng(), OBJ), n_samples=A(200, COUNT),
                                   optimiser=A("pso", OPT), swarm_options=A(SwarmOptions(iterations=5), ()))
    from fusion.estimates.chernoff.mixture import _mixture_arrays
    lw_b, m_b, c_b = _mixture_arrays([gA, gB])
    R[ch + "fuse_mixtures_batch"] = dict(weights=A(np.exp(lw_b)[None], BATCH), means=A(m_b[None], BATCH),
                                         covs=A(c_b[None], BATCH), rngs=A([rng()], ("str", "len")),
                                         n_samples=A(200, COUNT), eps0=A(np.array([0.4, 0.6]), BATCH + ("len",)),
                                         optimiser=A("pso", OPT), swarm_options=A(SwarmOptions(iterations=5), ()))
    fk = "fusion.filtering.kalman."
    F, Q, H, Rm, P0 = o["F"], o["Q"], o["H"], o["R"], o["P0"]
    R[fk + "cv_model"] = dict(T=A(1.0, POS))
    R[fk + "gain_sequence"] = dict(F=A(F, ARR + ("lensq",)), H=A(H, ARR), Q=A(Q, PSD), R=A(Rm, COV), P0=A(P0, PSD),
                                   n_steps=A(5, COUNT))
    R[fk + "split_covariances"] = dict(gains=A(o["gains"], OBJ), Q=A(Q, PSD), R=A(Rm, COV), P0d=A(0.5 * P0, PSD),
                                       P0i=A(0.5 * P0, PSD))
    R[fk + "filter_runs"] = dict(z=A(o["z"], ARR), gains=A(o["gains"], OBJ), x0=A(o["x0"], ARR + ("len",)))
    est = np.random.default_rng(7).normal(size=(3, 5, 4))
    traj5 = np.column_stack([np.arange(5.0), np.ones(5), np.zeros(5), np.zeros(5)])
    R[fk + "error_moments"] = dict(gains=A(o["gains"], OBJ), truth=A(traj5, ARR + ("len",)), R=A(Rm, COV),
                                   mean0=A(np.zeros(4), ARR + ("len",)), cov0=A(0.5 * P0, PSD))
    R[fk + "rmse_per_step"] = dict(estimates=A(est, ARR), truth=A(est[0] * 0.5, ARR + ("len",)))
    R[fk + "nees"] = dict(errors=A(est[0], ("nan", "inf", "empty", "more", "str", "len")),
                          covariances=A(np.stack([P0] * 5), ("nan", "inf", "empty", "more", "str", "nonsym", "indef", "negdef", "sing")))
    ft = "fusion.filtering.tracks."
    R[ft + "local_track"] = dict(z=A(o["z"], ARR), F=A(F, ARR + ("lensq",)), H=A(H, ARR), Q=A(Q, PSD), R=A(Rm, COV),
                                 x0=A(o["x0"], ARR + ("len",)), P0d=A(0.5 * P0, PSD), P0i=A(0.5 * P0, PSD))
    R[ft + "fuse_tracks"] = dict(a=A(o["ta"], OBJ), b=A(o["tb"], OBJ), rule=A("ci", OPT), omega=A(0.4, UNIT),
                                 criterion=A("trace", OPT))
    ff = "fusion.filtering.feedback."
    R[ff + "fusion_loop"] = dict(z1=A(o["z"], ARR), z2=A(o["z"] + 0.1, ARR + ("len",)), x0_1=A(o["x0"], ARR + ("len",)),
                                 x0_2=A(o["x0"], ARR + ("len",)), F=A(F, ARR + ("lensq",)), H=A(H, ARR), Q=A(Q, PSD),
                                 R1=A(Rm, COV), R2=A(2 * Rm, COV), P0d=A(0.5 * P0, PSD), P0i_1=A(0.5 * P0, PSD),
                                 P0i_2=A(0.5 * P0, PSD), rule=A("split", OPT), feedback=A("split", OPT),
                                 process_noise=A("own", OPT), omega=A(0.4, UNIT))
    fp = "fusion.filtering.particles."
    parts = np.random.default_rng(8).normal(size=(50, 4)) * 10 + np.array([100.0, 1.0, 50.0, 1.0])
    sensor = np.array([0.0, 0.0])
    R[fp + "ncv_model"] = dict(T=A(1.0, POS), q=A(0.5, POS))
    R[fp + "range_bearing"] = dict(states=A(parts, ("nan", "inf", "str", "lencol")), sensor=A(sensor, ARR + ("len",)))
    from fusion.filtering.particles import log_likelihood, range_bearing as rb_fn
    zz = rb_fn(parts[:1], sensor)[0]
    R[fp + "log_likelihood"] = dict(particles=A(parts, ("nan", "inf", "empty", "str", "lencol")), z=A(zz, ARR + ("len",)),
                                    sensor=A(sensor, ARR + ("len",)), sigma_r=A(10.0, POS), sigma_theta=A(0.05, POS))
    wts = np.full(50, 1 / 50)
    R[fp + "systematic_resample"] = dict(weights=A(wts, ARR + ("neg_entry",)), rng=A(rng(), OBJ))
    ll = log_likelihood(parts, zz, sensor, 10.0, 0.05)
    R[fp + "effective_sample_size"] = dict(weights=A(wts, ARR + ("neg_entry",)))
    R[fp + "weighted_moments"] = dict(x=A(parts, ("nan", "inf", "empty", "str", "more")), w=A(wts, ARR + ("len", "neg_entry")))
    R[fp + "wrap_angle"] = dict(a=A(np.array([0.1, -3.5, 7.0]), ("nan", "inf", "str")))
    R[fp + "regularise"] = dict(particles=A(parts, ("nan", "inf", "empty", "str", "lencol", "more")),
                                cov=A(np.eye(4), PSD), rng=A(rng(), OBJ))
    op = "fusion.optimise."
    R[op + "scalar.fruit_fly"] = dict(f=A(_quad, OBJ), rng=A(rng(), OBJ), population=A(5, COUNT), iterations=A(5, COUNT),
                                      lo=A(0.0, REAL), hi=A(1.0, REAL))
    R[op + "scalar.fruit_fly_batch"] = dict(f=A(lambda w: (w - 0.3) ** 2, OBJ), rngs=A([rng(), rng()], OBJ),
                                            population=A(5, COUNT), iterations=A(5, COUNT), lo=A(0.0, REAL), hi=A(1.0, REAL))
    R[op + "scalar.grid_search"] = dict(f=A(_quad, OBJ), n=A(11, COUNT), lo=A(0.0, REAL), hi=A(1.0, REAL))
    R[op + "scalar.bounded_minimum"] = dict(f=A(_quad, OBJ), lo=A(0.0, REAL), hi=A(1.0, REAL), xatol=A(1e-8, POS))
    R[op + "swarm.particle_swarm"] = dict(fitness=A(_quad_vec, OBJ), dim=A(2, COUNT), rng=A(rng(), OBJ),
                                          n_particles=A(5, COUNT), iterations=A(5, COUNT), inertia=A(0.7, NONNEG),
                                          c1=A(1.5, NONNEG), c2=A(1.5, NONNEG), vmax=A(0.2, POS),
                                          lo=A(1e-6, ("neg", "above", "nan_s", "str")), tol=A(1e-9, NONNEG),
                                          patience=A(3, COUNT), stop=A("stagnation", OPT), xtol=A(1e-3, POS),
                                          trace=A(False, ("str",)))
    R[op + "swarm.particle_swarm_batch"] = dict(fitness=A(_quad_batch, OBJ), dim=A(2, COUNT), rngs=A([rng(), rng()], ("str",)),
                                                n_particles=A(5, COUNT), iterations=A(5, COUNT), inertia=A(0.7, NONNEG),
                                                c1=A(1.5, NONNEG), c2=A(1.5, NONNEG), vmax=A(0.2, POS),
                                                lo=A(1e-6, ("neg", "above", "nan_s", "str")), tol=A(1e-9, NONNEG),
                                                patience=A(3, COUNT), stop=A("stagnation", OPT), xtol=A(1e-3, POS),
                                                trace=A(False, ("str",)))
    R[op + "swarm.check_swarm_options"] = dict(swarm_options=A(SwarmOptions(iterations=3, stop="positions"), ("str", "int")))
    R[op + "swarm.SwarmOptions"] = dict(n_particles=A(5, COUNT), iterations=A(5, COUNT), inertia=A(0.7, NONNEG),
                                        c1=A(1.5, NONNEG), c2=A(1.5, NONNEG), vmax=A(0.2, POS),
                                        lo=A(1e-6, ("neg", "above", "nan_s", "str")), tol=A(1e-9, NONNEG),
                                        patience=A(3, COUNT), stop=A("stagnation", OPT), xtol=A(1e-3, POS))
    rg = "fusion.registration.methods."
    R[rg + "two_point"] = dict(t=A(T_REG, ARR), z=A(Z_REG, ARR + ("len",)), t_query=A(TQ, ("nan", "inf", "more", "str")))
    R[rg + "three_point"] = dict(t=A(T_REG, ARR), z=A(Z_REG, ARR + ("len",)), t_query=A(TQ, ("nan", "inf", "more", "str")))
    R[rg + "least_squares"] = dict(t=A(T_REG, ARR), z=A(Z_REG, ARR + ("len",)), t_query=A(TQ, ("nan", "inf", "more", "str")),
                                   window=A(0.5, POS))
    R[rg + "blair_ls"] = dict(z_block=A(Z_REG[:4], ARR), tau=A(0.1, POS))
    R[rg + "ca_transition"] = dict(dt=A(0.1, REAL))
    R[rg + "kalman_filter"] = dict(t=A(T_REG, ARR), z=A(Z_REG, ARR + ("len",)), sigma=A(0.5, POS), q_v=A(0.01, NONNEG),
                                   q_a=A(0.001, NONNEG))
    R[rg + "kalman_register"] = dict(t=A(T_REG, ARR), z=A(Z_REG, ARR + ("len",)), t_query=A(TQ, ("nan", "inf", "more", "str")),
                                     sigma=A(0.5, POS), q_v=A(0.01, NONNEG), q_a=A(0.001, NONNEG))
    R[rg + "improved_register"] = dict(t=A(T_REG, ARR), z=A(Z_REG, ARR + ("len",)), t_query=A(TQ, ("nan", "inf", "more", "str")),
                                       sigma=A(0.5, POS), q_v=A(0.01, NONNEG), q_a=A(0.001, NONNEG))
    # issue 17: Q readings, vectorised filter / RTS smoother, quadratic LS, spline
    R[rg + "process_noise"] = dict(dt=A(0.5, NONNEG), q_v=A(0.01, NONNEG), q_a=A(0.001, NONNEG),
                                   model=A("per-step", OPT + ("notstr",)), period=A(2.0, POS))
    R[rg + "kalman_runs"] = dict(t=A(T_REG, ARR), Z=A(np.vstack([Z_REG, Z_REG + 0.1]), ("nan", "inf", "empty", "str", "lencol")),
                                 sigma=A(0.5, POS), q_v=A(0.01, NONNEG), q_a=A(0.001, NONNEG),
                                 q_model=A("white-noise jerk", OPT + ("notstr",)), init=A("once", OPT + ("notstr",)),
                                 p0=A((100.0, 100.0), ("str", "nested_neg_flat")), t_extra=A(TQ, ("nan", "inf", "more", "str")),
                                 period=A(0.1, POS))
    R[rg + "quadratic_ls"] = dict(t=A(T_REG, ARR), z=A(Z_REG, ARR + ("len",)), t_query=A(TQ, ("nan", "inf", "more", "str")),
                                  lookahead=A(1, ("neg", "frac", "str")))
    R[rg + "spline_register"] = dict(t=A(T_REG, ARR), z=A(Z_REG, ARR + ("len",)), t_query=A(TQ, ("nan", "inf", "more", "str")))
    R["fusion.registration.analysis.affine_decomposition"] = dict(register=A(_linear_register, OBJ), z0=A(Z_REG[:6], ARR))
    R["fusion.registration.analysis.expected_mse"] = dict(register=A(_linear_register, OBJ), z0=A(Z_REG[:6], ARR),
                                  truth_at_query=A(Z_REG[:5], ARR + ("len",)), sigma=A(0.5, NONNEG))
    R[rg + "sample_times"] = dict(first=A(0.0, REAL), period=A(0.1, POS), end=A(1.0, REAL))
    bk = "fusion.book."
    R[bk + "style.use_book_style"] = dict()
    R[bk + "style.color"] = dict(method=A("ci", ("notstr",)))
    R[bk + "style.method_style"] = dict(method=A("mean", ("notstr", "unknown")), markers=A(True, ()))  # unknown names are grey (documented)
    R[bk + "study_cache.study_cache"] = dict(maxsize=A(4, ("neg", "frac", "str")))
    R[bk + "study_cache.process_cache"] = dict(maxsize=A(4, ("neg", "frac", "str")))
    R[bk + "study_cache.study_key"] = dict(qualname=A("m.f", ()), arguments=A({"x": 1}, ()), digest=A("0" * 64, ("notstr",)))
    R[bk + "study_cache.source_digest"] = dict(package=A(str(Path(__file__).resolve().parents[1] / "fusion"), ("notstr",)))
    R[bk + "style.is_registered_label"] = dict(label=A("published", ("notstr",)))
    R[bk + "tables.side_by_side"] = dict(published=A(np.array([1.0, 2.0]), ("nan", "inf", "empty", "more", "str", "len")),
                                         reproduced=A(np.array([1.1, 2.1]), ("nan", "inf", "more", "str", "len")),
                                         index=A([1, 2], ("len",)), decimals=A(4, ("neg", "frac", "str")))
    R[bk + "tables.rounded"] = dict(value=A(1.23456, ("str",)), decimals=A(4, ("neg", "frac", "str")))
    R[bk + "audit.in_convex_hull"] = dict(x=A(X5, ARR), value=A(10.2, REAL), tol=A(0.0, NONNEG))
    R[bk + "audit.matching_subsets"] = dict(x=A(X5, ARR), target=A(10.1, REAL), tol=A(0.05, NONNEG), fuse=A(np.mean, OBJ))
    R[bk + "audit.implied_sum_change"] = dict(x=A(X5, ARR), published_mean=A(10.0, REAL))
    R[bk + "audit.parameters_matching"] = dict(x=A(X5, ARR), target=A(10.2, REAL), method=A("support_degree", OPT),
                                               name=A("alpha", OPT), lo=A(1e-3, POS), hi=A(10.0, POS), n_grid=A(20, COUNT))
    sn = "fusion.scenarios."
    R[sn + "infrared_radar.spherical_to_cartesian"] = dict(r=A(np.array([100.0, 200.0, 50.0]), ("nan", "inf", "str", "neg_entry")),
                                                           az=A(np.array([0.1, 0.2, 0.3]), ("nan", "inf", "str", "len")),
                                                           el=A(np.array([0.0, 0.1, 0.2]), ("nan", "inf", "str", "len")))
    R[sn + "infrared_radar.cartesian_to_spherical"] = dict(p=A(np.array([[1.0, 2.0, 3.0]]), ("nan", "inf", "str", "lencol")))
    R[sn + "infrared_radar.truth"] = dict(T=A(0.1, POS), duration=A(1.0, POS), r0=A(1000.0, POS), az0=A(0.5, REAL),
                                          el0=A(0.3, REAL))
    R[sn + "infrared_radar.white_acceleration"] = dict(T=A(0.1, POS), sigma=A(1.0, NONNEG))
    R[sn + "infrared_radar.simulate"] = dict(rng=A(rng(), OBJ), runs=A(2, COUNT), T=A(0.1, POS), duration=A(0.5, POS),
                                             sigma_ir=A(1e-4, POS), sigma_angle=A(0.02, POS), sigma_range=A(5.0, POS),
                                             rate_sigma=A(0.5, POS), range_rate_sigma=A(400.0, POS), q_scale=A(1.0, POS))
    sim = o["sim"]
    R[sn + "infrared_radar.position"] = dict(range_est=A(sim.radar_range.est, ("nan", "inf", "str", "lencol")),
                                             angle_est=A(sim.ir.est, ("nan", "inf", "str", "lencol")))
    R[sn + "infrared_radar.rule_errors"] = dict(sim=A(sim, OBJ), rules=A(("split_ci",), ("str", "unknown_entry")))
    # a valid call with every scan counted (the causal bound is nan at the first scan: documented)
    R[sn + "infrared_radar.many_scan_bound"] = dict(path=A(sim.path, OBJ), sigma_ir=A(1e-4, POS), sigma_angle=A(0.02, POS),
                                                    sigma_range=A(5.0, POS), sensors=A("both", OPT), smoother=A(True, ()))
    R[sn + "infrared_radar.conversion_jacobian"] = dict(sph=A(np.array([[1000.0, 0.6, 0.4]]), ("nan", "inf", "str", "lencol")))
    R[sn + "infrared_radar.cartesian_tracks"] = dict(sim=A(sim, OBJ), sigma_acc=A(1.0, POS), velocity_sigma=A(400.0, POS))
    R[sn + "infrared_radar.cartesian_errors"] = dict(sim=A(sim, OBJ), tracks=A(o["ct"], OBJ),
                                                     rules=A(("split_ci",), ("str", "unknown_entry")))
    sc = o["sc"]
    R[sn + "range_bearing.RangeBearingScenario"] = dict(
        sensors=A(((0.0, 0.0), (2000.0, 0.0)), ("nan", "inf", "empty", "str", "lencol")), sigma_r=A(10.0, POS),
        sigma_theta=A(0.03, POS), T=A(1.0, POS), q=A(0.5, POS), frames=A(2, COUNT), n_particles=A(60, COUNT),
        n_components=A(1, COUNT), n_samples=A(60, COUNT), n_central=A(100, COUNT), em_iterations=A(2, COUNT),
        n_initial=A(0, ("neg", "frac", "str")), guard=A(0.0, ("neg", "nan_s", "inf_s", "str", "above")),
        central_guard=A(0.0, ("neg", "nan_s", "inf_s", "str", "above")), prev_optimiser=A("pso", OPT),
        literal_xtol=A(1e-3, POS))
    R[sn + "range_bearing.method_keys"] = dict(n_sensors=A(3, COUNT))
    from fusion.scenarios import fusion_networks as fnw
    R[sn + "fusion_networks.NetworkNode"] = dict(position=A((0.0, 0.0), ("nan", "inf", "str", "len")),
                                                 kind=A("range", OPT), sigma_r=A(10.0, POS), sigma_theta=A(0.03, POS))
    tiny_nodes = (fnw.NetworkNode((800.0, 700.0), "bearing"), fnw.NetworkNode((1000.0, 1050.0), "range"))
    R[sn + "fusion_networks.redundancy_scenarios"] = dict()
    R[sn + "fusion_networks.NetworkScenario"] = dict(
        name=A("tiny", ()), nodes=A(tiny_nodes, ("str",)), frames=A(1, COUNT), rounds=A(1, COUNT),
        truth=A((1000.0, 800.0), ("nan", "inf", "str", "len")), prior_std=A(40.0, POS), n_particles=A(30, COUNT),
        n_samples=A(30, COUNT), n_components=A(2, COUNT), em_iterations=A(2, COUNT), stages=A(1, COUNT))
    R[sn + "fusion_networks.premise_scenarios"] = dict()
    tiny_net = fnw.NetworkScenario("tiny", tiny_nodes, n_particles=30, n_samples=30, n_components=2, em_iterations=2,
                                   stages=1)
    R[sn + "fusion_networks.run_network_study"] = dict(sc=A(tiny_net, OBJ), seed=A(1, ("neg", "frac", "str")),
                                                       runs=A(2, COUNT))
    R[sn + "range_bearing.simulate_target"] = dict(sc=A(sc, OBJ), rng=A(rng(), OBJ))
    R[sn + "range_bearing.run_tracking"] = dict(sc=A(sc, OBJ), seed=A(np.random.SeedSequence(1), OBJ),
                                                swarm_options=A(SwarmOptions(iterations=3), ()))
    R[sn + "range_bearing.run_tracking_batch"] = dict(sc=A(sc, OBJ), seeds=A([np.random.SeedSequence(1)], ("str",)),
                                                      all_nodes=A([False], ("len",)), swarm_options=A(SwarmOptions(iterations=3), ()),
                                                      workers=A(1, COUNT))
    from fusion.scenarios.range_bearing import simulate_target
    truths = simulate_target(sc, rng()).truth[None]
    R[sn + "range_bearing.posterior_crb"] = dict(sc=A(sc, OBJ), truths=A(truths, ("nan", "inf", "str", "lencol", "less")))
    R[sn + "range_bearing.linearised_errors"] = dict(sc=A(sc, OBJ), common_prior=A(True, OBJ),
                                                     common_process=A(False, OBJ))
    R[sn + "thermocouples.simulate"] = dict(rng=A(rng(), OBJ), n_samples=A(10, COUNT),
                                            sigma=A(np.ones(3), ("nan", "inf", "empty", "more", "str", "len", "neg_entry")),
                                            truth=A(900.0, REAL), n_sensors=A(3, COUNT))
    zt = 900 + np.random.default_rng(9).normal(size=(20, 10))
    R[sn + "thermocouples.inject_failure"] = dict(z=A(zt, ("nan", "inf", "str", "empty", "less")),
                                                  sensors=A((4, 10), ("str",)), samples=A((5, 8), ("str",)),
                                                  biases=A((4.0, 8.0), ("str", "len")))
    R[sn + "thermocouples.random_failure"] = dict(z=A(zt, ("nan", "inf", "str", "empty", "less")), rng=A(rng(), OBJ),
                                                  mode=A("random size", OPT), sensors=A((4, 10), ("str",)),
                                                  samples=A((5, 8), ("str",)), biases=A((4.0, 8.0), ("str", "len")))
    meth = {"mean": {"method": "mean"}}
    R[sn + "thermocouples.absolute_errors"] = dict(z=A(zt, ("nan", "inf", "str", "empty")),
                                                   methods=A(meth, ("str",)), truth=A(900.0, REAL))
    R[sn + "thermocouples.monte_carlo"] = dict(seed=A(1, ("neg", "frac", "str")), n_runs=A(3, COUNT), methods=A(meth, ("str",)),
                                               sigma=A(np.ones(3), ("nan", "inf", "empty", "more", "str", "len", "neg_entry")), n_samples=A(10, COUNT),
                                               truth=A(900.0, REAL), n_sensors=A(3, COUNT))
    R[sn + "thermocouples.best_linear_abs_error"] = dict(sigma=A(np.ones(3), ("nan", "inf", "empty", "more", "str", "neg_entry")),
                                                         n_sensors=A(3, COUNT))
    R[sn + "two_mixtures.toy_mixtures"] = dict()
    R[sn + "two_mixtures.grid_log_normaliser"] = dict(gms=A([gA, gB], OBJ + ("len",)),
                                                      eps=A(np.array([0.4, 0.6]), ARR + ("len",)),
                                                      limit=A(6.0, POS), n=A(41, COUNT))
    R[sn + "two_sensor.fixed_weight_rule"] = dict(reading=A("shared", OPT), omega=A(0.5, UNIT))
    R[sn + "two_sensor.trajectory"] = dict(T=A(1.0, POS), speed=A(50.0, POS), turn_time=A(20.0, NONNEG))
    R[sn + "two_sensor.model_truth"] = dict(rng=A(rng(), OBJ), F=A(F, ARR + ("lensq",)), Q=A(Q, PSD),
                                            x0=A(np.zeros(4), ARR + ("len",)), n_steps=A(5, COUNT), runs=A(2, COUNT))
    R[sn + "two_sensor.architecture_study"] = dict(rng=A(rng(), OBJ), R1=A(np.eye(2) * 2500.0, COV),
                                                   R2=A(np.eye(2) * 900.0, COV), Q=A(np.diag([1.0] * 4), PSD),
                                                                   runs=A(2, COUNT), nees_runs=A(2, COUNT), T=A(5.0, POS),
                                                   velocity_sigma=A(100.0, POS), t_steady=A(20.0, NONNEG),
                                                   printed_omegas=A(np.array([0.5]), ("nan", "inf", "more", "str")),
                                                   placement_omegas=A(np.array([0.5]), ("nan", "inf", "more", "str")))
    R[sn + "two_sensor.q_scaling_study"] = dict(rng=A(rng(), OBJ), R1=A(np.eye(2) * 2500.0, COV),
                                                R2=A(np.eye(2) * 900.0, COV), Q=A(np.diag([1.0] * 4), PSD),
                                                scales=A(np.array([1.0, 0.5]), ("nan", "inf", "empty", "more", "str", "neg_entry")),
                                                runs=A(2, COUNT), nees_runs=A(2, COUNT), T=A(5.0, POS),
                                                velocity_sigma=A(100.0, POS), t_steady=A(20.0, NONNEG))
    R[sn + "two_sensor.path_by_period"] = dict(periods=A(np.array([5.0]), ("nan", "inf", "empty", "more", "str", "neg_entry")),
                                               sigma=A(150.0, POS), delta0=A(10.0, POS), velocity_sigma=A(100.0, POS),
                                               t_steady=A(20.0, NONNEG))
    R[sn + "two_sensor.process_noise"] = dict(T=A(1.0, POS), delta0=A(10.0, POS), reading=A("discrete white acceleration (G = [T²/2, T] per axis)", OPT))
    R[sn + "two_sensor.pcrb_steady"] = dict(T=A(1.0, POS), sigma=A(150.0, POS), Q=A(np.diag([1.0] * 4), PSD))
    R[sn + "two_sensor.straight_leg_floor"] = dict(T=A(5.0, POS), sigma=A(150.0, POS), legs=A((100.0, 30.0, 90.0), ()),
                                                   turn_time=A(20.0, POS), causal=A(True, ()))
    R[sn + "two_sensor.slip_steps_band"] = dict(rmse=A(52.7, POS), published=A(3.0, POS), decimals=A(0, ("neg", "frac", "str")))
    est_v = np.random.default_rng(9).normal(size=(3, 6, 4))
    R[sn + "two_sensor.rmse_variants"] = dict(est=A(est_v, ("nan", "inf", "empty", "more", "less", "str")),
                                              truth=A(np.zeros((6, 4)), ("nan", "inf", "empty", "more", "less", "str", "len")),
                                              steps=A(np.ones(6, dtype=bool), ("len", "str")))
    R[sn + "two_sensor.two_sensor_scenario"] = dict(R_a=A(np.eye(2), COV), R_b=A(2 * np.eye(2), COV),
                                                    Q=A(np.diag([0.0, 1.0, 0.0, 1.0]), PSD), rng=A(rng(), OBJ),
                                                    runs=A(2, COUNT), T=A(1.0, POS), velocity_sigma=A(100.0, POS))
    # ---- additions after issue 21: readings, registration, scenarios, book (issue 21b) ----
    R[rs + "belief_matrices"] = dict(x=A(XT, ("nan", "inf", "empty", "more", "less", "str")), scale=A(1.0, POS))
    from fusion.readings.fusion_set import belief_matrix
    Bm = belief_matrix(X5)
    R[rs + "row_sum_weights"] = dict(B=A(Bm, ("nan", "inf", "empty", "less", "str", "neg_entry")))
    R[rw + "learned_variance_limit"] = dict(variances=A(np.array([1.0, 2.0, 4.0]), BATCH + ("neg_entry",)))  # (..., n)
    R[rw + "lecture_samples_needed"] = dict(level=A(900.0, REAL),
                                            variances=A(np.array([0.25, 1.0, 4.0]), ("nan", "inf", "empty", "more", "less", "str", "neg_entry")),
                                            rel_sd=A(0.5, POS))
    R[rs + "perron_gap"] = dict(B=A(Bm, ("nan", "inf", "empty", "less", "str", "neg_entry")))
    R[rw + "lecture_variance_sd"] = dict(level=A(900.0, REAL), k=A(np.array([10, 100]), ("nan", "inf", "str", "neg_entry")),
                                         variances=A(np.array([0.25, 1.0, 4.0]), ("nan", "inf", "empty", "more", "less", "str", "neg_entry")))
    R[rc + "rejection_probability"] = dict(snapshots=A(XT, ("nan", "inf", "empty", "more", "less", "str")), sensor=A(1, ("neg", "frac", "str")),
                                           biases=A(np.array([0.0, 2.0, 5.0]), ("nan", "inf", "empty", "more", "str")),
                                           eps=A(3.0, ("neg", "nan_s", "inf_s", "str")))
    R[rr + "operation_counts"] = dict(N=A(6, COUNT), d=A(2, COUNT))
    R[rr + "ldl_as_written_count"] = dict(N=A(6, COUNT), d=A(2, COUNT))
    R[rr + "spd_inverse_count"] = dict(N=A(6, COUNT), d=A(2, COUNT))
    R[rr + "gesv_inverse_count"] = dict(N=A(6, COUNT), d=A(2, COUNT))
    tq_reg = np.array([0.35, 1.05])
    st_reg = np.column_stack([Z_REG, np.full(T_REG.size, 2.0), np.zeros(T_REG.size)])
    R[rg + "predict_to"] = dict(t=A(T_REG, ARR), states=A(st_reg, ("nan", "inf", "empty", "more", "less", "str", "len", "lencol")),
                                t_query=A(tq_reg, ("nan", "inf", "more", "str")))
    R[sn + "infrared_radar.rmse_by_rule"] = dict(sim=A(sim, OBJ))
    from fusion.scenarios.infrared_radar import rmse_by_rule
    rmse_ir = rmse_by_rule(sim)
    R[sn + "infrared_radar.late_means"] = dict(rmse=A(rmse_ir, OBJ), t=A(sim.t, ("nan", "inf", "empty", "more", "str", "len")),
                                               t_min=A(0.2, REAL))
    from fusion.scenarios import lecture_weighting as lw

    def sl(name: str) -> str:  # the key of a chapter-02 study: its defining submodule
        return f"{getattr(lw, name).__module__}.{name}"

    s4 = sn + "lecture_correlated."
    R[sl("awf_study")] = dict(sigma=A((0.5, 1.0, 2.0, 4.0), ("nan", "inf", "empty", "more", "less", "str", "neg_entry")),
                               levels=A((0.0, 900.0), ("nan", "inf", "empty", "more", "str")), k_max=A(100, COUNT),
                               runs=A(2, COUNT), seed=A(1, ("neg", "frac", "str")), ks=A((3, 100), ("empty", "str", "frac_entry")),
                               k_compare=A(100, COUNT))
    R[sl("belief_parameter_study")] = dict(sigma=A((0.5, 1.0, 2.0, 4.0), ("nan", "inf", "empty", "more", "str", "neg_entry")),
                                            x=A(900.0, REAL), params=A((0.5, 1.0), ("nan", "inf", "empty", "more", "str", "neg_entry")),
                                            snapshots=A(4, COUNT), shift=A(10.0, NONNEG), seed=A(1, ("neg", "frac", "str")),
                                            grid=A((0.5, 1.0), ("nan", "inf", "empty", "more", "str")),
                                            limit_scale=A(1.0, POS))
    from fusion.scenarios.lecture_weighting import belief_parameter_study
    bps = belief_parameter_study(params=(0.5, 1.0), grid=(0.5, 1.0), snapshots=4)
    R[sl("belief_spread")] = dict(s=A(bps, OBJ), kind=A("lec_bel_fuzzy", OPT), values=A((0.5, 1.0), ("nan", "inf", "empty", "more", "str")))
    R[sl("regime_study")] = dict(sigma=A((0.5, 1.0, 2.0, 4.0), ("nan", "inf", "empty", "more", "less", "str", "neg_entry")),
                                  samples=A(40, COUNT), runs=A(2, COUNT), seed=A(1, ("neg", "frac", "str")),
                                  amplitude=A(5.0, REAL), period=A(40.0, POS), step=A(10.0, REAL),
                                  change_at=A(20, ("neg", "frac", "str", "big")), forgetting=A(0.9, UNIT),
                                  window=A(5, COUNT), guard=A("abs", OPT), level=A(900.0, REAL), fast_period=A(10.0, POS),
                                  walk_step=A(1.0, NONNEG), walk_seed=A(3, ("neg", "frac", "str")), forgetting_alt=A(0.95, UNIT))
    R[sl("lumv_study")] = dict(sigma=A((0.5, 1.0, 2.0), ("nan", "inf", "empty", "more", "str", "neg_entry")),
                                x=A(900.0, REAL), k=A(10, COUNT), runs=A(6, COUNT), seed=A(1, ("neg", "frac", "str")),
                                chunk=A(2, COUNT))
    R[sl("symmetry_study")] = dict(sigma=A((0.5, 1.0, 2.0), ("nan", "inf", "empty", "more", "less", "str", "neg_entry")),
                                    x=A(900.0, REAL), k=A(10, COUNT), runs=A(3, COUNT), seed=A(1, ("neg", "frac", "str")))
    R[sl("variance_change_study")] = dict(sigma=A((0.5, 1.0, 2.0, 4.0), ("nan", "inf", "empty", "more", "less", "str", "neg_entry")),
                                           samples=A(40, COUNT), runs=A(2, COUNT), seed=A(1, ("neg", "frac", "str")),
                                           change_at=A(20, ("neg", "frac", "str", "big")), forgetting=A(0.9, UNIT),
                                           forgetting_alt=A(0.95, UNIT), changes=A((("c", {0: 2.0}),), ("str",)))
    R[sl("learned_limit_check")] = dict(ns=A((3, 4), ("empty", "str", "frac_entry")), draws=A(5, COUNT),
                                         seed=A(1, ("neg", "frac", "str")), log_range=A(4.0, POS))
    R[sl("learning_study")] = dict(r_sets=A(((1.0, 4.0, 9.0), (1.0, 2.0, 4.0, 8.0)), ("str", "nested_neg", "nested_nan")), epochs=A(20, COUNT),
                                    runs=A(3, COUNT), x=A(50.0, REAL), seed=A(1, ("neg", "frac", "str")),
                                    seed_two=A(2, ("neg", "frac", "str")), last=A(10, COUNT))
    R[sl("consistency_study")] = dict(sigma=A((0.5, 1.0, 1.5, 2.0), ("nan", "inf", "empty", "more", "less", "str", "neg_entry")),
                                       samples=A(20, COUNT), runs=A(2, COUNT), x=A(900.0, REAL), bias=A(30.0, REAL),
                                       fault_sensor=A(2, ("neg", "frac", "str", "big")), window=A((5, 15), ("str", "len")),
                                       seed=A(1, ("neg", "frac", "str")), seed_curve=A(2, ("neg", "frac", "str")),
                                       curve_draws=A(50, COUNT), index_guard=A("abs", OPT))
    R[sl("belief_study")] = dict(sigma=A((0.5, 1.0, 2.0, 4.0), ("nan", "inf", "empty", "more", "less", "str", "neg_entry")),
                                  x=A(900.0, REAL), seeds=A((1, 2, 3), ("str", "len")), snapshots=A(20, COUNT))
    R[s4 + "ridge_study"] = dict(xs=A((0.5, 3.0), ("nan", "inf", "empty", "more", "str")), ms=A((1, 5), ("empty", "str", "frac_entry")),
                                 m0=A(5, COUNT), sigma=A(1.0, POS), seed=A(1, ("neg", "frac", "str")),
                                 seed_vector=A(2, ("neg", "frac", "str")), draws=A(20, COUNT))
    R[s4 + "correlated_study"] = dict(sigma=A((1.0, 2.0, 3.0), ("nan", "inf", "empty", "more", "str", "neg_entry")),
                                      sigma_env=A(1.5, NONNEG), runs=A(20, COUNT), x=A((1.0, -2.0), ("nan", "inf", "empty", "more", "str", "len")),
                                      seed=A(1, ("neg", "frac", "str")), sizes=A((6, 60), ("empty", "str", "frac_entry")))
    sx = "fusion.scenarios."
    R[sx + "correlated_sensors.covariance"] = dict(own=A((1.0, 2.0), ("nan", "inf", "empty", "more", "str", "neg_entry")),
                                                   coupling=A((1.0, 2.0), ("nan", "inf", "empty", "more", "str", "len")),
                                                   env=A(1.0, ("neg", "nan_s", "inf_s", "str")))
    R[sx + "correlated_sensors.coupling_study"] = dict(
        scenarios=A({"c": {"own": (1.0, 2.0), "coupling": (1.0, 2.0), "env": 1.0}}, ("str", "empty_dict")),
        runs=A(5, COUNT), x=A(1.0, REAL), seed=A(1, ("neg", "frac", "str")),
        env_grid=A((0.0, 1.0), ("nan", "inf", "empty", "more", "str", "neg_entry")), env_far=A(50.0, POS))
    R[sx + "correlated_sensors.estimated_covariance_study"] = dict(
        scenarios=A({"c": {"own": (1.0, 2.0), "coupling": (1.0, 2.0), "env": 1.0}}, ("str", "empty_dict")),
        ns=A((5, 8), ("str", "empty_list", "frac_entry")), reps=A(3, COUNT), seed=A(1, ("neg", "frac", "str")),
        misstate=A(0.1, UNIT))
    R[sx + "correlated_sensors.oriented_covariance"] = dict(
        angles=A((0.0, 60.0, 120.0), ("nan", "inf", "empty", "more", "str")),
        sd=A((1.0, 3.0), ("nan", "inf", "empty", "more", "str", "neg_entry")), env=A(1.5, NONNEG))
    R[sx + "wavelet_sensors.seed_study"] = dict(
        seeds=A((1, 2), ("empty", "str", "frac_entry")), runs=A(3, COUNT), kind=A("sig_slow", OPT + ("notstr",)),
        mode=A("hard", OPT), normaliser=A("max", OPT), length=A(64, COUNT), level=A(2, COUNT))
    R[sx + "wavelet_sensors.config_label"] = dict(cfg=A({"wavelet": "db4", "level": 4, "threshold": "universal", "mode": "soft"}, ("str",)))
    R[sx + "wavelet_sensors.measurand"] = dict(kind=A("sig_heavisine", OPT + ("notstr",)), length=A(64, COUNT))
    est3 = 2.0 + np.random.default_rng(5).normal(size=(3, 2, 16))
    R[sx + "wavelet_sensors.error_metrics"] = dict(est=A(est3, ("nan", "inf", "empty", "str")),
                                                   truth=A(np.full((2, 16), 2.0), ("nan", "inf", "empty", "str")))
    R[sx + "wavelet_sensors.signal_study"] = dict(
        signals=A(("sig_constant", "sig_slow"), ("str", "empty_list", "unknown_entry")), modes=A(("hard",), ("str", "empty_list", "unknown_entry")),
        normalisers=A(("max", "median"), ("str", "empty_list", "unknown_entry")), length=A(64, COUNT), runs=A(3, COUNT),
        gains=A((1.0, 1.5, 0.8), ("nan", "inf", "empty", "more", "str", "neg_entry")),
        sigma=A((0.05, 0.1, 0.2), ("nan", "inf", "empty", "more", "str", "len", "neg_entry")), seed=A(1, ("neg", "frac", "str")),
        wavelet=A("db4", OPT), level=A(2, COUNT), threshold=A("universal", OPT))
    R[sx + "wavelet_sensors.variance_study"] = dict(
        length=A(128, COUNT), runs=A(3, COUNT), gains=A((1.0, 1.5, 0.8), ("nan", "inf", "empty", "more", "str", "neg_entry")),
        sigma=A((0.05, 0.1, 0.2), ("nan", "inf", "empty", "more", "str", "len", "neg_entry")), seed=A(1, ("neg", "frac", "str")),
        window=A(8, COUNT), readings=A(("batch", "window"), ("str", "empty_list")), mode=A("hard", OPT),
        normaliser=A("max", OPT))
    R[sx + "wavelet_sensors.mechanism_study"] = dict(
        length=A(64, COUNT), runs=A(3, COUNT), gains=A((1.0, 1.5, 0.8), ("nan", "inf", "empty", "more", "str", "neg_entry")),
        sigma=A((0.05, 0.1, 0.2), ("nan", "inf", "empty", "more", "str", "len", "neg_entry")), seed=A(1, ("neg", "frac", "str")),
        configs=A(({"wavelet": "db4", "level": 2, "threshold": "universal", "mode": "soft"},), ("str", "empty_list")),
        kind=A("sig_slow", OPT + ("notstr",)))
    R[sx + "ridge_sensors.plugin_study"] = dict(
        xs=A((0.0, 1.0), ("nan", "inf", "empty", "more", "str")), m=A(3, COUNT), sigma=A(1.0, POS), runs=A(5, COUNT),
        seed=A(1, ("neg", "frac", "str")), curve=A((0.0, 1.0), ("nan", "inf", "empty", "more", "str")),
        deltas=A((1.0, 2.0), ("nan", "empty", "str", "neg_entry")))
    R[sx + "ridge_sensors.vector_study"] = dict(
        runs=A(5, COUNT), seed=A(1, ("neg", "frac", "str")), scales=A((3.0,), ("nan", "inf", "empty", "more", "str", "neg_entry")),
        spread=A(0.05, POS), sigma=A((1.0, 1.5, 2.0), ("nan", "inf", "empty", "more", "str", "neg_entry")))
    R[sl("delete_weights")] = dict(estimates=A([[1.0, -2.0, 4.0]], ("nan", "inf", "str")),
                                    mask=A([[True, True, False]], ("str",)))
    R[sl("tail_study")] = dict(sigma=A((0.5, 1.0, 2.0), ("nan", "inf", "empty", "more", "str", "neg_entry")),
                                x=A(900.0, REAL), k=A(10, COUNT), runs=A(100, COUNT), seed=A(1, ("neg", "frac", "str")),
                                chunk=A(50, COUNT), thresholds=A((1.0, 10.0), ("nan", "inf", "str")))
    R[sl("ar1_study")] = dict(sigma=A((0.5, 1.0, 2.0), ("nan", "inf", "empty", "more", "str", "neg_entry")),
                               phi=A(0.5, ("nan_s", "inf_s", "str")), k=A(10, COUNT), runs=A(100, COUNT),
                               seed=A(1, ("neg", "frac", "str")))
    R[sl("benchmark")] = dict(seeds=A((1, 2), ("empty", "str", "frac_entry")), runs=A(2, COUNT), samples=A(20, COUNT),
                               levels=A((0.0, 900.0), ("nan", "inf", "empty", "more", "str")), bias=A(30.0, REAL),
                               fault_sensor=A(2, ("neg", "frac", "str", "big")), fault_from=A(10, ("neg", "frac", "str")),
                               sigma=A((0.5, 1.0, 1.5, 2.0), ("nan", "inf", "empty", "more", "less", "str", "neg_entry")))
    from fusion.scenarios.lecture_weighting import benchmark as lecture_benchmark
    bench = lecture_benchmark(seeds=(1, 2), runs=2, samples=20, fault_from=10)
    R[sl("seed_stability")] = dict(results=A(bench, ("str", "empty_dict")), n_se=A(3.0, POS))
    R[sn + "range_bearing.monte_carlo"] = dict(sc=A(sc, OBJ), seed=A(1, ("neg", "frac", "str")), runs=A(1, COUNT),
                                               all_nodes_first=A(False, ("str",)), workers=A(1, COUNT))
    runs_rb = o["runs_rb"]
    R[sn + "range_bearing.position_sq_errors"] = dict(runs=A(runs_rb, ("str", "empty_list")), key=A("centralised_pf", OPT + ("notstr",)))
    R[sn + "range_bearing.nees_per_frame"] = dict(runs=A(runs_rb, ("str", "empty_list")), key=A("centralised_pf", OPT + ("notstr",)))
    R[sn + "range_bearing.min_local_ess"] = dict(runs=A(runs_rb, ("str",)))
    sig10 = np.linspace(0.5, 2.0, 10)
    R[sn + "thermocouples.paired_study"] = dict(seed=A(1, ("neg", "frac", "str")), n_runs=A(2, COUNT),
                                                methods=A({"ofs": {"method": "optimal_fusion_set"}, "mean": {"method": "mean"}}, ("str",)),
                                                sigma=A(sig10, ("nan", "inf", "empty", "more", "str", "len", "neg_entry")),
                                                n_samples=A(90, COUNT), failure=A(None, ("str",)), truth=A(900.0, REAL),
                                                n_sensors=A(10, COUNT), failure_mode=A("fixed", OPT))
    R[sn + "thermocouples.scale_sweep"] = dict(seed=A(1, ("neg", "frac", "str")), n_runs=A(2, COUNT),
                                               scales=A(np.array([1.0, 2.0]), ("nan", "inf", "empty", "str", "neg_entry")),
                                               failure=A(None, ("str",)),
                                               sigma=A(sig10, ("nan", "inf", "empty", "more", "str", "len", "neg_entry")),
                                               window=A((50, 80), ("str",)))
    st = sn + "time_registration."
    t1s, t2s = np.arange(1.0, 20.0, 2.0), np.array([3.0, 8.0, 13.0])
    R[st + "truth"] = dict(t=A(t1s, ("nan", "inf", "str")))
    R[st + "instants"] = dict(period_2=A(5.0, POS))
    R[st + "manoeuvre_truth"] = dict(t=A(t1s, ("nan", "inf", "str")), a_after=A(0.0, REAL), t_change=A(20.0, REAL))
    R[st + "two_point_remainder"] = dict(t_src=A(t1s, ARR), t_dst=A(t2s, ("nan", "inf", "more", "str")))
    reg_args = dict(name=A("reg_two_point", OPT + ("notstr",)), t_src=A(t1s, ARR), t_dst=A(t2s, ("nan", "inf", "more", "str")),
                    sigma=A(2.0, POS), q_v=A(0.01, NONNEG), q_a=A(0.001, NONNEG))
    R[st + "registrar"] = dict(reg_args)
    R[st + "register"] = dict(reg_args, z=A(2.0 + t1s, ARR + ("len",)))
    R[st + "expected"] = dict(name=A("reg_kalman_two_point", OPT + ("notstr",)), sigma=A(2.0, POS), t_src=A(t1s, ARR),
                              t_dst=A(t2s, ("nan", "inf", "more", "str")), q_v=A(0.01, NONNEG), q_a=A(0.001, NONNEG))
    R[st + "monte_carlo"] = dict(names=A(("reg_two_point", "reg_kalman_two_point"), ("str", "unknown_entry")), sigma=A(2.0, POS),
                                 runs=A(2, ("neg", "frac", "str", "zero")), seed=A(1, ("neg", "frac", "str")), t_src=A(t1s, ARR),
                                 t_dst=A(t2s, ("nan", "inf", "more", "str")), q_v=A(0.01, NONNEG), q_a=A(0.001, NONNEG))
    R[st + "noise_free_mse"] = dict(name=A("reg_two_point", OPT + ("notstr",)), t_src=A(t1s, ARR),
                                    t_dst=A(t2s, ("nan", "inf", "more", "str")), sigma=A(2.0, POS),
                                    q_v=A(0.01, NONNEG), q_a=A(0.001, NONNEG))
    R[st + "noise_gain"] = dict(name=A("reg_two_point", OPT + ("notstr",)))
    R[st + "crossing_sigma"] = dict(a=A("reg_three_point", OPT + ("notstr",)), b=A("reg_two_point", OPT + ("notstr",)))
    R[st + "mse_coefficients"] = dict(name=A("reg_kalman_two_point", OPT + ("notstr",)), sigma_filter=A(2.0, POS),
                                      t_src=A(t1s, ARR), t_dst=A(t2s, ("nan", "inf", "more", "str")),
                                      q_v=A(0.01, NONNEG), q_a=A(0.001, NONNEG), kf=A({"init": "once"}, ("str",)))
    R[st + "fusion_runs"] = dict(names=A(("reg_two_point", "reg_kalman_two_point"), ("str", "unknown_entry")), sigma=A(2.0, POS),
                                 runs=A(2, ("neg", "frac", "str", "zero")), seed=A(1, ("neg", "frac", "str")))
    s2 = sn + "two_sensor."
    sc2 = o["sc2"]
    R[s2 + "fruit_fly_over_seeds"] = dict(P1=A(np.eye(2), COV), P2=A(np.diag([1.0, 0.2]), COV),
                                    seeds=A(np.arange(2), ("nan", "inf", "empty", "str", "neg_entry")),
                                    n_grid=A(11, COUNT), population=A(3, COUNT), iterations=A(3, COUNT),
                                    rtol=A(1e-9, NONNEG))
    Pp = sc2.tracks[0]
    R[s2 + "printed_fruit_fly_over_seeds"] = dict(P1d=A(Pp.Pd[3], PSD), P1i=A(Pp.Pi[3], PSD), P2d=A(sc2.tracks[1].Pd[3], PSD),
                                            P2i=A(sc2.tracks[1].Pi[3], PSD),
                                            seeds=A(np.arange(2), ("nan", "inf", "empty", "str", "neg_entry")),
                                            n_grid=A(11, COUNT), population=A(3, COUNT), iterations=A(3, COUNT),
                                            rtol=A(1e-9, NONNEG))
    R[s2 + "per_step_weights"] = dict(a=A(sc2.tracks[0], OBJ), b=A(sc2.tracks[1], OBJ), seed=A(1, ("neg", "frac", "str")),
                                      n_grid=A(11, COUNT), population=A(3, COUNT), iterations=A(3, COUNT))
    K2 = sc2.t.size
    R[s2 + "fusion_study"] = dict(sc=A(sc2, OBJ), w_fruit_fly=A(np.full(K2, 0.4), ("nan", "inf", "more", "str", "len", "neg_entry")),
                                  w_grid=A(np.full(K2, 0.6), ("nan", "inf", "more", "str", "len", "neg_entry")),
                                  published_omega=A(0.5, UNIT), t_steady=A(20.0, NONNEG))
    est2 = np.stack([tr.est for tr in sc2.tracks])[0]
    R[s2 + "run_rmse"] = dict(est=A(est2, ("nan", "inf", "empty", "more", "less", "str")),
                              truth=A(sc2.truth, ("nan", "inf", "str", "len")),
                              steps=A(sc2.t >= 20.0, ("str", "len", "none_selected")), component=A(0, ("neg", "frac", "str", "big")),
                              decimals=A(3, ("neg", "frac", "str")))
    R[s2 + "nees_study"] = dict(rng=A(rng(), OBJ), Q=A(np.diag([0.0, 1.0, 0.0, 1.0]), PSD), R1=A(np.eye(2) * 2500.0, COV),
                                R2=A(np.eye(2) * 2500.0, COV), x_start=A(np.array([0.0, 50.0, 0.0, 0.0]), ARR + ("len",)),
                                n_steps=A(25, COUNT), runs=A(2, COUNT), T=A(1.0, POS),
                                velocity_sigma=A(100.0, POS), t_steady=A(20.0, NONNEG))
    bl = bk + "ledger."
    from fusion.book.ledger import Comparison, Proposition, PublishedValues, Unverifiable
    ev = Proposition(True, "holds")
    R[bl + "fmt"] = dict(x=A(0.123456, ("str",)), digits=A(4, COUNT))
    R[bl + "ledger_dir"] = dict(start=A(Path(__file__).resolve().parent, ("notstr",)))
    R[bl + "Source"] = dict(key=A("k", ("notstr",)), short=A("A (2000)", ("notstr",)), title=A("T", ("notstr",)),
                            chapter=A("notebooks/x", ("notstr",)), order=A(1, COUNT))
    R[bl + "PublishedValues"] = dict(published=A(np.array([1.25, 2.5]), ("nan", "inf", "empty", "more", "str", "len")),
                                     ours=A(np.array([1.25, 2.5]), ("inf", "more", "str", "len")),
                                     decimals=A(2, ("neg", "frac", "str")), unit=A("m", ("notstr",)))
    ab = np.random.default_rng(10).normal(size=(2, 100))
    # +inf is a run whose statistic is infinite (rule R3 of the rulebook), not bad input
    R[bl + "Comparison"] = dict(a=A(ab[0], ("nan", "empty", "more", "less", "str", "len")),
                                b=A(ab[1], ("nan", "empty", "less", "str")), a_name=A("A", ("notstr",)),
                                b_name=A("B", ("notstr",)), claim=A("less", OPT + ("notstr",)), metric=A("MSE", ("notstr",)),
                                seed=A(1, ("frac", "str")), reason=A("", ("notstr",)), margin=A(0.1, NONNEG))
    R[bl + "Proposition"] = dict(holds=A(True, ("str",)), ours=A("it holds", ("notstr",)))
    R[bk + "exact.ExactComparison"] = dict(a=A(0.9, ("nan", "inf", "str")), b=A(1.0, ("nan", "inf", "str")),
                                           a_name=A("A", ("notstr",)), b_name=A("B", ("notstr",)),
                                           claim=A("less", OPT + ("notstr",)), metric=A("exact MSE", ("notstr",)),
                                           margin=A(0.05, NONNEG))
    R[bl + "Unverifiable"] = dict(reason=A("no data", ("notstr",)))
    R[bl + "Conjunction"] = dict(parts=A((("sensor 1", ev), ("sensor 2", Proposition(False, "fails"))), ("str", "empty_list")))
    R[bl + "Alternative"] = dict(choice=A("guard", ("notstr",)), reading=A("|x|", ("notstr",)), evidence=A(ev, ("str",)))
    R[bl + "Claim"] = dict(id=A("yang-x", ("notstr",)), source=A("yang2012optimal", OPT + ("notstr",)), where=A("Table 1", ("notstr",)),
                           claim=A("A is smaller", ("notstr",)), published=A("qualitative", ("notstr",)), evidence=A(ev, ("str",)),
                           link=A("sec-x", ("notstr",)), bound=A("", ("notstr",)), assumptions=A(("a",), ("str",)),
                           alternatives=A((), ("str",)), headline=A(False, ("str",)), critiques=A((), ("str",)))
    R[bl + "Ledger"] = dict(source=A("yang2012optimal", OPT + ("notstr",)))
    rb = bk + "rulebook."
    tb = bk + "tables."
    R[tb + "power_of_ten"] = dict(mantissa=A("1.5", ("notstr",)), exponent=A(-7, ("frac", "str")))
    R[tb + "sci"] = dict(x=A(1.5e-7, ("str",)), digits=A(4, COUNT))
    R[tb + "roundoff"] = dict(value=A(1.7e-15, REAL), exponent=A(-12, ("frac", "str")))
    R[tb + "cell_text"] = dict(text=A("nan", ("notstr",)))
    R[tb + "tidy_table_html"] = dict(html=A("<td>True</td>", ("notstr",)))
    R[bk + "style.plain_math"] = dict(text=A(r"$\sigma_1^2$", ("notstr",)))
    R[rb + "hill_tail_index"] = dict(x=A(ab[0], ("nan", "inf", "empty", "str")))
    R[rb + "median_interval"] = dict(d=A(ab[0], ("nan", "empty", "str")), level=A(0.95, UNIT))
    R[rb + "median_values_needed"] = dict(level=A(0.95, UNIT))
    R[rb + "share_interval"] = dict(wins=A(40, ("neg", "frac", "str")), runs=A(100, COUNT), level=A(0.95, UNIT))
    R[rb + "region"] = dict(low=A(-1.0, ("nan_s", "str")), high=A(1.0, ("nan_s", "str")), margin=A(0.5, NONNEG),
                            scale=A(2.0, NONNEG))
    R[rb + "status_from_region"] = dict(where=A("lower", OPT + ("notstr",)), direction=A("less", OPT + ("notstr",)))
    R[rb + "judge_paired"] = dict(a=A(ab[0], ("nan", "empty", "less", "str")), b=A(ab[1], ("nan", "empty", "less", "str")),
                                  direction=A("less", OPT + ("notstr",)), margin=A(0.1, NONNEG))
    R[rb + "counted"] = dict(kind=A("open-choice", OPT + ("notstr",)), runs=A(100, COUNT), primary_runs=A(100, COUNT))
    R[rb + "record_status"] = dict(primary=A("reproduced", OPT + ("notstr",)),
                                   readings=A((("open-choice", "reproduced", 100),), ("str",)),
                                   primary_runs=A(100, COUNT), assumptions=A(False, ()))
    R[bk + "glue.glue_all"] = dict(values=A({"x-a": 1.23456}, ("str",)), decimals=A(2, ("neg", "frac", "str")))
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from fusion.book.recommend import Evidence as _Ev
    from fusion.book.recommend import Recommendation as _Rec
    from fusion.book.tables import side_by_side as _sbs

    def _fig():
        f, a = plt.subplots(figsize=(4.0, 3.0))
        a.plot([0.0, 1.0], [0.0, 1.0], color="k")
        return f

    R[bk + "figures.allowed_colors"] = dict()
    R[bk + "figures.audit_figure"] = dict(fig=A(_fig(), OBJ))
    R[bk + "figures.glue_figure"] = dict(key=A("fig-key", ("notstr",)), fig=A(_fig(), OBJ))
    tab = _sbs([1.0, 2.0], [1.0, 2.1], [1, 2])
    R[bk + "tables.mismatches"] = dict(table=A(tab, OBJ), decimals=A(2, ("neg", "frac", "str")))
    R[bk + "tables.highlight_mismatches"] = dict(table=A(tab, OBJ), decimals=A(2, ("neg", "frac", "str")),
                                                 uuid=A("t1", ("notstr",)))
    R[bk + "tables.integral_index"] = dict(table=A(tab, OBJ))
    ev = _Ev("a", ("reproduced",), "role")
    R[bk + "recommend.Evidence"] = dict(claim=A("a", ("notstr",)), expect=A(("reproduced",), ("str", "unknown_entry")),
                                        role=A("role", ("notstr",)))
    R[bk + "recommend.Recommendation"] = dict(task=A("t", ("notstr",)), use=A("u", ("notstr",)), why=A("w", ("notstr",)),
                                              avoid=A("a", ("notstr",)), avoid_why=A("b", ("notstr",)),
                                              evidence=A((ev,), ("str",)), chapters=A(("c",), ("str",)))
    R[bk + "recommend.check"] = dict(records=A([{"id": "a", "status": "reproduced"}], ("str",)),
                                     recommendations=A([_Rec("t", "u", "w", "a", "b", (ev,), ())], ("str",)))
    R[bk + "benchmarks.load_benchmark"] = dict(name=A("ci", OPT + ("notstr",)), results=A(None, ("notstr",)))
    _set_every_parameter(R)
    return R


#: Mutations of a ``bool`` flag (rule 18: a string or a number is not read as its truthiness).
FLAG = ("str", "int")
#: Mutations of a text option.
TEXT_OPT = ("unknown", "notstr")
#: Mutations of an optional number whose ``None`` default is valid (the scalar kinds apply to any value).
OPT_NUM = ("nan_s", "str")


def _set_every_parameter(R: dict[str, dict[str, A]]) -> None:
    """Set, in the valid calls above, the parameters they left at their defaults (fuzz 24a, class U: 105 parameters
    no sweep had ever mutated; ``tests/test_bad_input_fuzz24_params.py`` checks that every parameter is set here or
    exempt there). The value is the default (or a valid value where the default is ``None``)."""
    def add(_callable: str, **params: A) -> None:
        spec = R["fusion." + _callable]
        assert not set(params) & set(spec), f"{_callable}: {sorted(set(params) & set(spec))} already set"
        spec.update(params)

    add("book.exact.ExactComparison", relative_margin=A(None, OPT_NUM))
    add("book.figures.glue_figure", alt=A(None, ("notstr",)))
    add("book.ledger.Alternative", kind=A("open-choice", TEXT_OPT))
    add("book.ledger.Claim", claimant=A("source", TEXT_OPT), test=A("", TEXT_OPT))
    add("book.ledger.Comparison", relative_margin=A(None, OPT_NUM), conditions=A(("", ""), ("str", "int")),
        infinite_mean=A((), ("str", "unknown_entry")))
    add("book.ledger.Ledger", chapter=A(None, TEXT_OPT))
    add("book.ledger.Proposition", runs=A(None, ("zero", "neg", "frac", "str")))
    add("book.ledger.PublishedValues", runs=A(None, ("zero", "neg", "frac", "str")))
    add("book.ledger.Source", chapters=A(("notebooks/x",), ("str", "int")))
    add("book.rulebook.counted", status=A(None, TEXT_OPT))
    add("book.rulebook.judge_paired", infinite_mean=A((), ("str", "unknown_entry")))
    add("book.tables.highlight_mismatches", precision=A(None, ("neg", "frac", "str")))
    add("book.tables.side_by_side", name=A("", ("notstr",)), index_name=A("observation", ("notstr",)))
    add("estimates.chernoff.chernoff_fuse_gaussians", on_simplex=A(True, FLAG))
    add("estimates.chernoff.first_order_fusion", simplified=A(False, FLAG))
    add("estimates.chernoff.fuse_mixtures", eps0=A(None, ("str",)), redraw=A(False, FLAG), reference=A(False, FLAG),
        timed=A(False, FLAG))
    add("estimates.chernoff.fuse_mixtures_batch", redraw=A(False, FLAG), reference=A(False, FLAG), timed=A(False, FLAG),
        keep_samples=A(False, FLAG))
    add("estimates.ci.split_ci_objective", same_omega=A(False, FLAG))
    add("estimates.ci.split_covariance_intersection", same_omega=A(False, FLAG))
    add("estimates.mixtures.weighted_em", init=A(None, ("str", "int")))
    add("estimates.mixtures.weighted_em_batch", init=A(None, ("str", "int", "empty_list")))
    add("filtering.kalman.split_covariances", R_shared=A(None, ("str",)))
    add("filtering.particles.effective_sample_size", axis=A(-1, (("past_end", 99), "frac", "str", ("below", -3))))
    add("filtering.tracks.local_track", R_shared=A(None, ("str",)))
    add("optimise.scalar.fruit_fly", step=A((30.0, -10.0), ("empty", "nan", "inf", "str", "less", ("three", (1.0, 2.0, 3.0)))),
        vectorized=A(False, FLAG))
    add("optimise.scalar.fruit_fly_batch", step=A((30.0, -10.0), ("empty", "nan", "inf", "str", "less")))
    add("optimise.scalar.grid_search", vectorized=A(False, FLAG))
    add("optimise.simplex.check_simplex", name=A("eps", ("notstr",)))
    add("optimise.simplex.minimise_on_simplex", jac=A(None, ("str",)), x0=A(None, ("str", ("off", (0.5, 0.6)))),
        ftol=A(1e-14, POS))
    add("optimise.swarm.check_swarm_options", name=A("swarm_options", ("notstr",)))
    add("readings.consistency.consistency_awf", adjacent=A("sorted", TEXT_OPT))
    add("readings.fusion_set.belief_degree", binary_eps=A(None, ("neg", "nan_s", "str")))
    add("readings.fusion_set.belief_matrix", binary_eps=A(None, ("neg", "nan_s", "str")))
    for f in ("distribution_balance", "fusion_set_weights", "optimal_fusion_set"):
        add("readings.fusion_set." + f, include_self=A(True, FLAG))
    add("readings.robust.robust_fuse", sigma=A(None, ("str", "nan_s", "neg")), cut=A(0.1, ("neg", "nan_s", "str", "above")),
        c=A(1.345, POS), alpha=A(0.05, UNIT), k=A(3.0, POS))
    add("readings.weighting.awf", guard=A("floor", TEXT_OPT))
    add("readings.weighting.inverse_variance_weights", guard=A("floor", TEXT_OPT))
    add("readings.weighting.ls_learning", corrected=A(False, FLAG))
    for f in ("improved_register", "three_point", "two_point"):
        add("registration.methods." + f, causal=A(False, FLAG))
    add("registration.methods.kalman_filter", q_model=A("per-step", TEXT_OPT), init=A("source", TEXT_OPT),
        p0=A((100.0, 100.0), ("empty", "nan", "str", "less", "neg_entry")), t_extra=A(None, ("str", ("nan", [np.nan]))),
        period=A(2.0, POS))
    add("registration.methods.kalman_runs", smooth=A(False, FLAG), lag_one=A(False, FLAG))
    add("registration.methods.quadratic_ls", past=A(None, ("zero", "neg", "frac", "str")))
    add("scenarios.fusion_networks.NetworkNode", model_scale=A(1.0, POS), relay_of=A(None, ("neg", "frac", "str")))
    add("scenarios.fusion_networks.NetworkScenario", edges=A(None, ("str", "int", ("float_pair", ((0.0, 1.5),)),
                                                                   ("self_loop", ((1, 1),)))))
    add("scenarios.infrared_radar.truth", velocity=A((300.0, 100.0, 0.0), ("empty", "nan", "inf", "str", "less")))
    add("scenarios.lecture_correlated.ridge_study", ks_fixed=A((0.01, 0.1, 1.0), ("empty", "nan", "str", "neg_entry")),
        x_far=A(273.65, REAL))
    add("scenarios.lecture_weighting.learning.learned_limit_check", margin=A(0.05, NONNEG))
    add("scenarios.lecture_weighting.readings_benchmark.benchmark", faults=A((False, True), ("str", "int", "empty_list",
                                                                                           ("number", (0.1,)))))
    add("scenarios.range_bearing.RangeBearingScenario", x0=A((800.0, 15.0, 600.0, 10.0), ("empty", "nan", "inf", "str", "less")),
        p0_std=A((30.0, 3.0, 30.0, 3.0), ("empty", "nan", "inf", "str", "less", "neg_entry")),
        regularised=A(True, FLAG), variants=A(True, FLAG), readings=A(False, FLAG))
    add("scenarios.range_bearing.method_keys", readings=A(False, FLAG))
    add("scenarios.range_bearing.run_tracking", all_nodes=A(False, FLAG))
    add("scenarios.thermocouples.monte_carlo", failure=A(None, ("str", ("unknown_key", {"no_such_key": 1}))))
    add("scenarios.thermocouples.simulate", n_runs=A(None, ("zero", "neg", "frac", "str")))
    reg_options = dict(kf=A(None, ("str", ("unknown_key", {"no_such_key": 1}))), window=A(None, POS))
    add("scenarios.time_registration.expected", **reg_options, sigma_filter=A(None, POS), delay=A(0.0, REAL),
        a_after=A(None, REAL), t_change=A(20.0, REAL))
    add("scenarios.time_registration.monte_carlo", **reg_options, sigma_filter=A(None, POS), delay=A(0.0, REAL),
        a_after=A(None, REAL), t_change=A(20.0, REAL))
    add("scenarios.time_registration.register", **reg_options)
    add("scenarios.time_registration.registrar", **reg_options)
    add("scenarios.two_mixtures.grid_log_normaliser", return_density=A(False, FLAG))
    add("scenarios.two_sensor.path_by_period", readings=A(("as printed: Δ₀² I per step",), ("str", "unknown_entry",
                                                                                            "empty_list", ("number", 0.1))))
    add("scenarios.two_sensor.trajectory", start=A((300.0, 0.0), ("empty", "nan", "inf", "str", "less")),
        legs=A((100.0, 30.0, 90.0), ("empty", "nan", "inf", "str", "less", "neg_entry")))


#: Result and data types: frozen containers returned by the functions, not input-taking functions.
RESULT_TYPES = {
    "fusion.readings.fusion_set.ReadingsFusion", "fusion.readings.fusion_set.EpochFusion",
    "fusion.readings.weighting.AWFResult", "fusion.readings.wavelet.Reconstruction",
    "fusion.estimates.ci.FusedEstimate", "fusion.estimates.fuzzy_cluster.ClusterFusion",
    "fusion.estimates.chernoff.ChernoffGaussian", "fusion.estimates.chernoff.MixtureFusion",
    "fusion.filtering.kalman.GainSequence", "fusion.filtering.tracks.LocalTrack",
    "fusion.filtering.tracks.FusedTracks", "fusion.optimise.result.OptimumResult", "fusion.optimise.result.SwarmTrace",
    "fusion.scenarios.infrared_radar.IrRadarRuns", "fusion.scenarios.infrared_radar.CartesianTracks",
    "fusion.scenarios.range_bearing.TrackingRun", "fusion.scenarios.two_sensor.Scenario",
    "fusion.scenarios.fusion_networks.NetworkStudy",
    "fusion.book.audit.SubsetMatch", "fusion.data._published.Published",
    "fusion.book.benchmarks.BenchmarkResult", "fusion.scenarios.thermocouples.PairedStudy",
    "fusion.scenarios.time_registration.MonteCarlo", "fusion.scenarios.two_sensor.FusionStudy",
    "fusion.scenarios.time_registration.FusionRuns",
    "fusion.scenarios.two_sensor.FruitFlySeeds",
    # the figure audit's exception type
    "fusion.book.figures.FigureStyleError",
    # the rulebook's result and rule records (built by its functions, which the registry covers)
    "fusion.book.rulebook.Judgement", "fusion.book.rulebook.Rule",
    # alt-text and notebook-formatting hooks on matplotlib figures, PNG bytes and the notebook's display
    # (checked by tests/test_figures.py and tests/test_book_tables_format.py)
    "fusion.book.style.describe_figure", "fusion.book.style.figure_alt", "fusion.book.style.set_figure_alt",
    "fusion.book.style.png_description", "fusion.book.tables.use_book_tables",
    # figure helpers: thin wrappers of matplotlib, checked by the notebooks' figures
    "fusion.book.style.new_figure",
    # marks an array read-only; accepts any array by design
    "fusion.data._published.read_only",
    # method keys (an enumeration of strings, not an input-taking function)
    "fusion.scenarios.two_sensor.StudyMethod", "fusion.scenarios.two_sensor.Architecture",
    "fusion.scenarios.two_sensor.ArchRule", "fusion.scenarios.infrared_radar.IrMethod",
    "fusion.scenarios.two_sensor.NeesRule", "fusion.scenarios.time_registration.RegMethod",
}
#: Frozen results of the functions that returned bare tuples before (issue 12, item 5).
RESULT_TYPES |= {f"fusion.{name}" for name in (
    "estimates.mixtures.Moments", "estimates.mixtures.EmFit", "estimates.chernoff.FirstOrderMixture", "estimates.chernoff.FusionTimings",
    "scenarios.range_bearing.LinearisedErrors",
    "filtering.kalman.CvModel", "filtering.kalman.SplitCovariances", "filtering.particles.NcvModel",
    "filtering.particles.WeightedMoments", "readings.biased.RidgeMoments", "readings.consistency.ConsistentAWF",
    "readings.correlated.LinearEstimate", "readings.correlated.LDLFactors", "readings.biased.RidgeFit", "readings.fusion_set.MeanDistances",
    "readings.biased.PluginRisk",
    "readings.weighting.LSLearning", "registration.methods.BlairEstimate", "registration.methods.FilteredStates",
    "registration.analysis.AffineDecomposition", "scenarios.infrared_radar.Truth",
    "scenarios.range_bearing.SimulatedTarget", "scenarios.two_mixtures.ToyMixtures",
    "scenarios.two_mixtures.GridLogNormaliser", "scenarios.two_sensor.Trajectory",
    "filtering.feedback.FusionLoop", "scenarios.two_sensor.ArchitectureStudy", "filtering.kalman.ErrorMoments",
    "scenarios.two_sensor.QScaling",
    "scenarios.lecture_weighting.readings_benchmark.SeedStability",
    "scenarios.lecture_weighting.readings_benchmark.BenchMethod",
    "scenarios.lecture_weighting.estimators.TailStudy", "scenarios.lecture_weighting.estimators.AR1Study",
    "scenarios.lecture_weighting.learning.LearnedLimitCheck", "scenarios.lecture_weighting.estimators.SymmetryStudy",
    "scenarios.lecture_weighting.belief.BeliefStudy", "scenarios.lecture_weighting.estimators.LumvStudy",
    "scenarios.lecture_weighting.learning.LearningStudy", "scenarios.lecture_weighting.consistency.ConsistencyStudy",
    "scenarios.lecture_weighting.regime.RegimeStudy", "scenarios.lecture_weighting.regime.VarianceChangeStudy",
    "scenarios.lecture_weighting.estimators.AwfStudy", "scenarios.lecture_weighting.belief.BeliefParameterStudy",
    "scenarios.lecture_weighting.estimators.AwfMethod", "scenarios.lecture_weighting.consistency.FaultDiagnostics",
    "scenarios.lecture_weighting.regime.RegimeMethod", "scenarios.lecture_weighting.belief.PerronStats",
    "scenarios.lecture_weighting.regime.RegimeScenario", "scenarios.lecture_weighting.regime.VarianceChange",
    "scenarios.lecture_weighting.estimators.ConstantLevelRuns",
    "scenarios.range_bearing.TrackingTimings",
    "scenarios.lecture_weighting.belief.BeliefKind", "scenarios.lecture_weighting.learning.LearningRow",
    "scenarios.lecture_weighting.estimators.EstimatorRow",
    # chapters 03-04's study results (issue 36), built by the validated study functions
    "scenarios.wavelet_sensors.SignalStudy", "scenarios.wavelet_sensors.SeedStudy",
    "scenarios.wavelet_sensors.MechanismStudy", "scenarios.wavelet_sensors.VarianceStudy",
    "scenarios.ridge_sensors.PluginStudy", "scenarios.ridge_sensors.VectorStudy",
    "scenarios.correlated_sensors.CouplingStudy", "scenarios.correlated_sensors.EstimatedCovarianceStudy",
    "scenarios.lecture_correlated.RidgeStudy", "scenarios.lecture_correlated.CorrelatedStudy",
    # chapter 05's NEES study result (issue 36), built by the validated nees_study
    "scenarios.two_sensor.NeesStudy",
    # keys (issue 36): chapter 07's information classes, chapter 06's networks, the ridge option of chapter 03,
    # chapter 04's coupling cases
    "scenarios.time_registration.Information", "scenarios.fusion_networks.Network", "readings.biased.ShrinkAt",
    "scenarios.correlated_sensors.CouplingCase",
    # chapter 02's E2.3 data sets (issue 36)
    "scenarios.lecture_weighting.consistency.FaultCase",
    # chapter 03's measured signals (issue 36)
    "scenarios.wavelet_sensors.Signal")}


def _extra_mutation(value: Any, how: str) -> Any:
    if how == "frac_entry":  # integer counts with a fraction among them
        return (2.5,) + tuple(value)[1:]
    if how in ("nested_neg", "nested_nan"):  # a sequence of sequences with a bad number inside
        first = (-1.0 if how == "nested_neg" else float("nan"),) + tuple(value[0])[1:]
        return (first,) + tuple(value)[1:]
    if how == "big":  # an index past the end
        return 99
    if how == "nested_neg_flat":  # a negative entry in a short tuple of numbers
        return (-1.0,) + tuple(value)[1:]
    if how == "empty_dict":
        return {}
    if how == "unknown_key":  # an options dict with a key its consumer does not take
        return dict(value, no_such_key=1)
    if how == "none_val":  # an options dict with a value of the wrong type
        return {k: None for k in value}
    if how == "int":
        return 3
    if how == "empty_list":
        return []
    if how == "unknown_entry":
        return tuple(value) + ("no-such-option",)
    if how == "none_selected":
        return np.zeros_like(value, dtype=bool)
    if how == "lencol":
        x = _arr(value)
        return x[..., :-1]
    if how == "neg_entry":
        x = _arr(value)
        x.flat[0] = -abs(x.flat[0]) - 1.0
        return x
    if how == "ll_nan":
        v = value.values.copy()
        v[0] = np.nan
        return _Loglik(v)
    if how == "ll_neginf":  # every particle impossible
        return _Loglik(np.full_like(value.values, -np.inf))
    if how == "ll_len":
        return _Loglik(value.values[:-1])
    return mutate(value, how)


def _finite(result: Any) -> bool:
    if isinstance(result, (float, np.floating)):
        return bool(np.isfinite(result))
    if isinstance(result, np.ndarray):
        return not np.issubdtype(result.dtype, np.floating) or bool(np.all(np.isfinite(result)))
    if isinstance(result, (tuple, list)):
        return all(_finite(r) for r in result)
    if isinstance(result, dict):
        return all(_finite(r) for r in result.values())
    if dataclasses.is_dataclass(result):
        # documented NaN: FusedEstimate.omega of methods without a weight (convex combination)
        return all(_finite(getattr(result, f.name)) for f in dataclasses.fields(result)
                   if f.name not in ("timings", "history") and not (f.name == "omega" and type(result).__name__ == "FusedEstimate"))
    return True


CALLABLES = public_callables()
REG = registry()


#: Left out of this registry: the chapter layer ``fusion.book.chapters`` has its own registries of valid calls, one
#: per group of chapters (``tests/test_bad_input_calls_ch*.py``, swept by :func:`refusal_problems`;
#: ``tests/test_bad_input_calls_cover.py`` checks that together they cover every public chapter function).
EXCLUDED_PREFIXES = ("fusion.book.chapters.",
                     # file- and cluster-bound: the claim files' schema errors (naming file, record and field) are
                     # tested in tests/test_rulebook.py, the sweep's failures in tests/test_stability.py
                     "fusion.book.claims.", "fusion.book.stability.")


def _excluded(name: str) -> bool:
    return name.startswith(EXCLUDED_PREFIXES)


def test_registry_covers_every_public_callable() -> None:
    missing = sorted(n for n in set(CALLABLES) - set(REG) - RESULT_TYPES if not _excluded(n))
    assert not missing, f"public callables without a valid example call: {missing}"
    stale = sorted(set(REG) - set(CALLABLES))
    assert not stale, f"registry entries that are not public callables: {stale}"


#: Callables whose registry entry still finds unrefused bad input (validation not yet added):
#: a strict xfail, so that the entry fails loudly as soon as the function is fixed and must leave this set.
PENDING_VALIDATION: set[str] = set()


def _fresh(kwargs: dict[str, Any]) -> dict[str, Any]:
    """The arguments with every generator replaced by a fresh seeded one (each call draws the same numbers)."""
    return {k: (np.random.default_rng(0) if isinstance(v, np.random.Generator) else v) for k, v in kwargs.items()}


def _bad_values(a: A) -> list[tuple[str, Any]]:
    """The mutated values of one argument: a named mutation kind, or an explicit ``(label, value)`` pair."""
    out = []
    for how in a.mutations:
        if isinstance(how, tuple):
            out.append(how)
            continue
        bad = _extra_mutation(a.value, how)
        if bad is not None:
            out.append((how, bad))
    return out


def refusal_problems(name: str, fn: Callable[..., Any], spec: dict[str, A]) -> list[str]:
    """Run the valid call of ``spec``, then each mutated call; return what was not refused by name.

    The valid call must give a finite result. Each mutated call must raise ``ValueError`` or ``TypeError`` whose
    message names the mutated argument (either argument of a pair for the ``len*`` mutations); any other exception,
    an accepted call, or a message naming neither is a problem. Shared by every registry of valid calls (the main
    package here, the chapter layer in ``tests/chapter_calls/``).
    """
    valid = {k: a.value for k, a in spec.items()}
    result = fn(**_fresh(valid))
    _close_figures(result)
    if not _finite(result):
        return [f"{name}: the valid call gave a non-finite result"]
    problems = []
    for arg, a in spec.items():
        for how, bad in _bad_values(a):
            kwargs = _fresh(valid)
            kwargs[arg] = bad
            try:
                out = fn(**kwargs)
            except (ValueError, TypeError) as exc:
                # a mismatch is a property of the pair: naming either argument is enough
                names = spec if how.startswith("len") else [arg]
                if not any(re.search(rf"(?<![A-Za-z0-9_]){re.escape(n)}(?![A-Za-z0-9_])", str(exc)) for n in names):
                    problems.append(f"{arg}/{how}: {type(exc).__name__} does not name {arg!r}: {exc}")
                continue
            except Exception as exc:  # noqa: BLE001 - any other exception is a failure
                problems.append(f"{arg}/{how}: {type(exc).__name__}: {exc}")
                continue
            _close_figures(out)
            finite = "finite" if _finite(out) else "NON-FINITE"
            problems.append(f"{arg}/{how}: accepted ({finite} result)")
    return problems


def _close_figures(result: Any) -> None:
    """Close the matplotlib figures a call returned (alone or in a tuple), so a sweep keeps no figure open."""
    import matplotlib.pyplot as plt
    from matplotlib.figure import Figure

    for r in result if isinstance(result, tuple) else (result,):
        if isinstance(r, Figure):
            plt.close(r)


def group_names(callables: dict[str, Any], excluded: dict[str, str], pending: dict[str, str]) -> list[Any]:
    """The parameters of a chapter registry's sweep: every public name of the group but the excluded ones, a strict
    xfail (with its reason) for each pending one. Names, not the registry: collection, which every xdist worker
    runs, builds no study; :func:`check_group` checks that they are the registry's keys."""
    return [pytest.param(n, marks=pytest.mark.xfail(strict=True, reason=pending[n])) if n in pending else n
            for n in sorted(set(callables) - set(excluded))]


def check_group(callables: dict[str, Any], reg: dict[str, Any], excluded: dict[str, str]) -> None:
    """A chapter registry holds a valid call of every public function of its group but the excluded ones, and
    nothing else."""
    missing = sorted(set(callables) - set(reg) - set(excluded))
    assert not missing, f"public functions of the group without a valid call: {missing}"
    stale = sorted((set(reg) | set(excluded)) - set(callables))
    assert not stale, f"entries that are not public functions of the group: {stale}"
    assert not set(reg) & set(excluded), "a function both in the registry and excluded"


def group_tests(callables: dict[str, Any], registry: Callable[[], dict[str, dict[str, A]]], excluded: dict[str, str],
                pending: dict[str, str]) -> tuple[Callable[[], None], Callable[[str], None]]:
    """The two tests of a chapter registry (``tests/test_bad_input_calls_ch*.py``), bound to its group: the
    registry covers the group (:func:`check_group`), and each function's sweep (:func:`refusal_problems`) finds
    nothing, parametrised by :func:`group_names`. A module binds them as ``test_registry_covers_the_group,
    test_bad_input_is_refused = group_tests(...)``."""

    def covers() -> None:
        check_group(callables, registry(), excluded)

    @pytest.mark.parametrize("name", group_names(callables, excluded, pending))
    def refused(name: str) -> None:
        problems = refusal_problems(name, callables[name], registry()[name])
        assert not problems, f"{name}:\n  " + "\n  ".join(problems)

    return covers, refused


@pytest.mark.parametrize("name", [pytest.param(n, marks=pytest.mark.xfail(strict=True, reason="validation pending"))
                                  if n in PENDING_VALIDATION else n for n in sorted(REG)])
def test_bad_input_is_refused(name: str) -> None:
    problems = refusal_problems(name, CALLABLES[name], REG[name])
    assert not problems, f"{name}:\n  " + "\n  ".join(problems)


# --------------------------------------------------------------------------------------------
# the bugs named in issue 21
# --------------------------------------------------------------------------------------------


def _spd(rng: np.random.Generator, cond: float, n: int = 4) -> np.ndarray:
    Qm, _ = np.linalg.qr(rng.normal(size=(n, n)))
    A = (Qm * np.logspace(0.0, np.log10(cond), n)) @ Qm.T
    return 0.5 * (A + A.T)


def _accurate_size(w: float, P1: np.ndarray, P2: np.ndarray, criterion: str) -> float:
    """CI criterion from the inverse-free form P(w) = P2 (w P2 + (1-w) P1)^-1 P1 (reference)."""
    P = P2 @ np.linalg.solve(w * P2 + (1.0 - w) * P1, P1)
    P = 0.5 * (P + P.T)
    return float(np.trace(P)) if criterion == "trace" else float(np.linalg.slogdet(P)[1])


@pytest.mark.parametrize("criterion", ["trace", "det"])
@pytest.mark.parametrize("cond", [1e2, 1e6, 1e10, 1e12])
def test_ci_weight_matches_a_fine_grid_at_high_condition_numbers(cond: float, criterion: str) -> None:
    from fusion.estimates.ci import ci_weight

    rng = np.random.default_rng(int(np.log10(cond)))
    grid = np.linspace(0.0, 1.0, 2001)
    for _ in range(5):
        P1, P2 = _spd(rng, cond), _spd(rng, cond / 100)
        w = ci_weight(P1, P2, criterion)
        assert 0.0 <= w <= 1.0
        best = min(_accurate_size(g, P1, P2, criterion) for g in grid)
        # the reference itself is accurate to about cond * 1e-16 relative
        assert _accurate_size(w, P1, P2, criterion) <= best + 1e-5 * abs(best) + 1e-9


def test_ci_weight_of_the_issue_pair_is_interior() -> None:
    """Condition numbers 6e10 and 1.3e8: an eigenvalue rounding to -2.7e-13 used to give omega = 1."""
    from fusion.estimates.ci import ci_weight

    rng = np.random.default_rng(21)
    for _ in range(20):
        P1, P2 = _spd(rng, 6e10), _spd(rng, 1.3e8)
        for criterion in ("trace", "det"):
            w = ci_weight(P1, P2, criterion)
            grid = np.linspace(0.0, 1.0, 1001)
            vals = [_accurate_size(g, P1, P2, criterion) for g in grid]
            best = min(vals)
            assert _accurate_size(w, P1, P2, criterion) <= best + 1e-6 * abs(best) + 1e-9


def test_ci_weight_at_condition_1e16_returns_a_weight_without_raising() -> None:
    from fusion.estimates.ci import ci_weight, covariance_intersection

    rng = np.random.default_rng(16)
    for _ in range(10):
        P1, P2 = _spd(rng, 1e16), _spd(rng, 1e14)
        for criterion in ("trace", "det"):
            try:
                w = ci_weight(P1, P2, criterion)
            except ValueError as exc:  # numerically not positive definite: refused by name
                assert "P1" in str(exc) or "P2" in str(exc)
                continue
            assert 0.0 <= w <= 1.0
            r = covariance_intersection(np.zeros(4), P1, np.ones(4), P2, criterion=criterion)
            assert np.all(np.isfinite(r.x)) and np.all(np.isfinite(r.P))


def test_ci_weight_is_scale_invariant_at_extreme_scales() -> None:
    from fusion.estimates.ci import ci_weight

    P1 = np.array([[2.0, 0.3], [0.3, 1.0]])
    P2 = np.array([[1.0, -0.2], [-0.2, 3.0]])
    for criterion in ("trace", "det"):
        w = ci_weight(P1, P2, criterion)
        for s in (1e-12, 1e12):
            assert ci_weight(s * P1, s * P2, criterion) == pytest.approx(w, abs=1e-9)


@pytest.mark.parametrize("n_sensors", [1, 2, 4])
def test_distributed_tracking_runs_with_any_number_of_sensors(n_sensors: int) -> None:
    from fusion.scenarios import range_bearing as rb

    sensors = ((0.0, 0.0), (2000.0, 0.0), (1000.0, 2000.0), (0.0, 2000.0))[:n_sensors]
    sc = rb.RangeBearingScenario(sensors=sensors, frames=2, n_particles=100, n_samples=100, n_central=150,
                                 em_iterations=2, n_components=2)
    run = rb.run_tracking(sc, np.random.SeedSequence(5), swarm_options=SwarmOptions(iterations=3))
    assert sorted(run.estimates) == sorted(rb.method_keys(n_sensors))
    assert [k for k in run.estimates if k.startswith("local")] == [f"local{i + 1}" for i in range(n_sensors)]
    for v in run.estimates.values():
        assert v.shape == (2, 4) and np.all(np.isfinite(v))
    assert run.eps["pso"].shape == (2, n_sensors)
    np.testing.assert_allclose(run.eps["pso"].sum(axis=1), 1.0)
    if n_sensors == 1:  # one sensor: every exponent weight is 1
        np.testing.assert_allclose(run.eps["pso"], 1.0)


def test_run_tracking_refuses_an_empty_sensor_list() -> None:
    from fusion.scenarios import range_bearing as rb

    with pytest.raises(ValueError, match="sensors"):
        rb.RangeBearingScenario(sensors=())


def test_mixture_log_density_refuses_points_of_the_wrong_dimension() -> None:
    from fusion.estimates.mixtures import gm_logpdf

    gA = _objects()["gA"]
    with pytest.raises(ValueError, match="x must have 2 columns"):
        gm_logpdf(gA, np.zeros((5, 3)))
    with pytest.raises(ValueError, match="x must have 2 columns"):
        gm_logpdf(gA, np.zeros(3))


def test_split_ci_does_not_reshape_a_flat_vector() -> None:
    from fusion.estimates.ci import split_covariance_intersection

    with pytest.raises(ValueError, match="P1d"):
        split_covariance_intersection(v1, np.array([2.0, 0.0, 0.0, 1.0]), P1, v2, P2, P2)


@pytest.mark.parametrize("floor", [0.0, -1e-3, np.nan])
def test_inverse_variance_weights_refuse_a_floor_that_is_not_positive(floor: float) -> None:
    from fusion.readings.weighting import inverse_variance_weights

    with pytest.raises(ValueError, match="floor"):
        inverse_variance_weights(np.array([1.0, -0.5, 2.0]), floor=floor)


def test_particle_helpers_refuse_zero_particles_and_impossible_likelihoods() -> None:
    from fusion.filtering import particles as pf

    rng = np.random.default_rng(0)
    with pytest.raises(ValueError, match="weights"):
        pf.systematic_resample(np.empty(0), rng)
    with pytest.raises(ValueError, match="weights"):
        pf.effective_sample_size(np.empty(0))
    with pytest.raises(ValueError, match="x"):
        pf.weighted_moments(np.empty((0, 4)), np.empty(0))


# --------------------------------------------------------------------------------------------
# degenerate but valid input: documented behaviour
# --------------------------------------------------------------------------------------------


def test_one_sensor() -> None:
    from fusion.estimates.chernoff import chernoff_fuse_gaussians, fuse_mixtures
    from fusion.estimates.fuzzy_cluster import fuzzy_cluster_fusion
    from fusion.readings import fusion_set as fs
    from fusion.readings.weighting import awf, inverse_variance_weights

    for f in (fs.arithmetic_mean, fs.optimal_fusion_set, fs.support_degree, fs.belief_degree, fs.fusion_set_weights):
        r = f([7.5])
        assert r.value == 7.5 and np.array_equal(r.weights, [1.0])
    np.testing.assert_array_equal(inverse_variance_weights([[2.0]]), [[1.0]])
    c = fuzzy_cluster_fusion(v1[None], P1[None])
    np.testing.assert_array_equal(c.x, v1)
    g = chernoff_fuse_gaussians(v1[None], P1[None], [1.0])
    np.testing.assert_allclose(g.x, v1)
    np.testing.assert_allclose(g.P, P1)
    assert g.log_normaliser == pytest.approx(0.0, abs=1e-12)
    fu = fuse_mixtures([_objects()["gA"]], np.random.default_rng(0), n_samples=100, swarm_options=SwarmOptions(iterations=3))
    np.testing.assert_allclose(fu.eps, [1.0])
    with pytest.raises(ValueError, match="at least 2 sensors"):  # variances need a partner sensor
        awf(np.ones((5, 1)))


def test_identical_readings_and_estimates() -> None:
    from fusion.estimates.ci import ci_weight, covariance_intersection
    from fusion.readings import fusion_set as fs
    from fusion.readings.consistency import consistency_mask
    from fusion.readings.weighting import inverse_variance_weights

    x = np.full(6, 3.25)
    for f in (fs.arithmetic_mean, fs.optimal_fusion_set, fs.support_degree, fs.belief_degree, fs.fusion_set_weights):
        r = f(x)
        assert r.value == pytest.approx(3.25, abs=1e-15)
        np.testing.assert_allclose(r.weights, np.full(6, 1 / 6))
    assert consistency_mask(x, 0.0).all()
    np.testing.assert_allclose(inverse_variance_weights(np.full((1, 4), 2.0)), np.full((1, 4), 0.25))
    assert ci_weight(P1, P1) == 0.5  # flat criterion: the symmetric weight (documented)
    r = covariance_intersection(v1, P1, v1, P1)
    np.testing.assert_allclose(r.x, v1)
    np.testing.assert_allclose(r.P, P1)


@pytest.mark.parametrize("omega", [0.0, 1.0])
def test_omega_at_the_ends(omega: float) -> None:
    from fusion.estimates.chernoff import log_normaliser_two_gaussians
    from fusion.estimates.ci import ci_objective, covariance_intersection, split_covariance_intersection

    r = covariance_intersection(v1, P1, v2, P2, omega=omega)
    x, P = (v1, P1) if omega == 1.0 else (v2, P2)
    np.testing.assert_allclose(r.x, x, atol=1e-12)
    np.testing.assert_allclose(r.P, P, atol=1e-12)
    assert ci_objective(omega, P1, P2) == pytest.approx(np.trace(P))
    assert log_normaliser_two_gaussians(v1, P1, v2, P2, omega) == pytest.approx(0.0, abs=1e-12)
    # split CI divides the correlated parts by omega and 1 - omega: the ends are refused by name
    with pytest.raises(ValueError, match="omega"):
        split_covariance_intersection(v1, P1, 0.5 * P1, v2, P2, 0.5 * P2, omega=omega)


def test_stationary_target_in_the_infrared_radar_case() -> None:
    from fusion.scenarios import infrared_radar as ir

    sim = ir.simulate(np.random.default_rng(0), runs=2, duration=0.5, velocity=(0.0, 0.0, 0.0))
    assert sim.sigma_acc == {"az": 0.0, "el": 0.0, "range": 0.0}
    np.testing.assert_array_equal(ir.white_acceleration(0.1, 0.0), np.zeros((2, 2)))
    for err in ir.rule_errors(sim).values():
        assert np.all(np.isfinite(err))


def test_target_on_a_sensor() -> None:
    from fusion.filtering.particles import range_bearing
    from fusion.scenarios import infrared_radar as ir
    from fusion.scenarios import range_bearing as rb

    # range 0 and, by the atan2 convention, bearing 0 (documented: the bearing is undefined there)
    np.testing.assert_array_equal(range_bearing(np.array([5.0, 1.0, 7.0, 1.0]), np.array([5.0, 7.0])), [0.0, 0.0])
    with pytest.raises(ValueError, match="range 0"):
        ir.cartesian_to_spherical(np.zeros(3))
    sc = _objects()["sc"]
    truths = np.zeros((1, 2, 4))  # on sensor 1 at the origin
    with pytest.raises(ValueError, match="coincides with sensor 1"):
        rb.posterior_crb(sc, truths)


@pytest.mark.parametrize("scale", [1e-12, 1e12])
def test_extreme_scales(scale: float) -> None:
    from fusion.estimates.ci import covariance_intersection
    from fusion.readings import fusion_set as fs

    x = scale * np.array([1.0, 1.01, 0.99, 1.02, 1.5])
    for f in (fs.arithmetic_mean, fs.optimal_fusion_set, fs.support_degree, fs.fusion_set_weights):
        r = f(x)
        assert np.isfinite(r.value) and x.min() <= r.value <= x.max()
    base = 1e12 + np.array([0.0, 1e-3, 2e-3, -1e-3])  # a 1e-3 spread on a 1e12 level
    r = fs.optimal_fusion_set(base)
    assert base.min() <= r.value <= base.max()
    r = covariance_intersection(scale * v1, scale**2 * P1, scale * v2, scale**2 * P2, criterion="det")
    ref = covariance_intersection(v1, P1, v2, P2, criterion="det")
    assert r.omega == pytest.approx(ref.omega, abs=1e-9)
    np.testing.assert_allclose(r.x / scale, ref.x, rtol=1e-9)
