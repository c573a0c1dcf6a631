r"""Lecture §2.4 (E2.4, E2.4b): belief-degree weights.

Belief-degree weights against a shift (:func:`belief_study`), and how much the fused value depends on the analyst's
parameter (:func:`belief_parameter_study`, :func:`belief_spread`).
"""

from __future__ import annotations

from dataclasses import dataclass
from collections.abc import Mapping, Sequence
from enum import StrEnum
import numpy as np
from numpy.typing import ArrayLike

from fusion._guards import own_underflow
from fusion import readings as rd
from fusion._results import (NONNEGATIVE, ResultSpec, array, arrays, dict_of, flag, instance, mask, number, trusted,
                             tuple_of, validated_post_init)
from fusion._frozen import constant
from fusion._validation import derived_inputs
from fusion._validation import allocation, count, instance_of, one_of, scalar, sequence
from fusion._validation import LOOP_STEP, distinct, distinct_printed, general, loop_work, work
from fusion._validation import store_read
from fusion.scenarios._lecture_checks import _seed, _sigmas, _values
from fusion._shown import shown

__all__ = [
    "PerronStats",
    "ZERO_WEIGHT",
    "BeliefStudy",
    "belief_study",
    "BeliefKind",
    "BELIEF_KINDS",
    "DELETION_SUPPORT",
    "BeliefParameterStudy",
    "belief_parameter_study",
    "belief_spread",
]


# --------------------------------------------------------------------------- E2.4
#: A Perron weight (the weights sum to 1) at most this is zero up to round-off (:attr:`PerronStats.share_zero_weight`).
ZERO_WEIGHT = 1e-12


@dataclass(frozen=True)
class PerronStats:
    """The Perron statistics of one kind of belief matrix over the snapshots of :func:`belief_study`.

    Attributes
    ----------
    min_gap : float
        Smallest relative gap of :func:`fusion.readings.fusion_set.perron_gap`.
    share_repeated : float
        Share of snapshots whose gap is at most ``fusion.readings.fusion_set.PERRON_RTOL`` (a repeated Perron root).
    min_weight : float
        Smallest weight.
    share_zero_weight : float
        Share of snapshots with a reading of weight 0, up to round-off (at most :data:`ZERO_WEIGHT`: a reducible
        belief matrix's Perron vector has exact zeros, computed as about ±10⁻¹⁵, whose sign moves with
        the BLAS kernel; the other weights of the book's snapshots are above 0.01).
    min_lambda : float
        Smallest largest eigenvalue.
    lambda_is_modulus : bool
        Whether the largest eigenvalue is the largest in modulus on every snapshot.
    max_residual : float
        Largest ‖BA − λA‖/(λ‖A‖) for the returned weights A.
    """

    min_gap: float
    share_repeated: float
    min_weight: float
    share_zero_weight: float
    min_lambda: float
    lambda_is_modulus: bool
    max_residual: float

    # min_weight: an exact zero is computed as about ±10⁻¹⁵ (any sign); a weight of weights summing to 1 is at most 1
    __result_spec__ = ResultSpec(
        {"min_gap": number(bounds=(0.0, 1.0)), "share_repeated": number(bounds=(0.0, 1.0)),
         "min_weight": number(nonnegative=False, bounds=(-np.inf, 1.0)), "share_zero_weight": number(bounds=(0.0, 1.0)),
         "min_lambda": number(positive=True), "lambda_is_modulus": flag(), "max_residual": number()})
    __post_init__ = validated_post_init


@dataclass(frozen=True)
class BeliefStudy:
    """Experiment E2.4: belief-degree (Perron eigenvector) weights (:func:`belief_study`).

    Attributes
    ----------
    base : ndarray, shape (n,)
        The one draw of the sensors.
    deltas : ndarray, shape (201,)
        The shifts Δ of reading 1.
    W : ndarray, shape (201, n)
        The weights against Δ.
    unit_k_maxdiff, unit_f_maxdiff, unit_fconv_maxdiff, unit_f_valdiff : float
        Largest weight differences in K, in °F and in °F with the scale converted, and the °F fused value's
        difference (converted back) from the °C one.
    eig_w, row_w : ndarray, shape (snapshots, n)
        Eigenvector and row-sum weights of the snapshots.
    rowsum_maxdiff, rowsum_valdiff_rms : float
        Largest weight difference and RMS fused-value difference between the two.
    mse_eig, mse_row : float
        Fused MSE of each.
    sq_eig, sq_row : ndarray, shape (snapshots,)
        Squared errors per snapshot.
    shifted : ndarray of bool, shape (snapshots,)
        Reading 1 shifted.
    perron : mapping of str to PerronStats
        Belief matrix and its parameter (``"fuzzy, s = 1"``, ``"binary, ε = 2"``, ``"truncated, m = 4"``) → its Perron
        statistics, for fuzzy (s = 0.25, 1, 4), binary (ε = 0.5, 1, 2, 4) and truncated fuzzy (s = 1, m = 1, 2, 4)
        belief matrices of the same snapshots.
    bin_lam : tuple of float
        The binary belief matrix's two largest eigenvalues.
    bin_w : ndarray, shape (4,)
        Its weights (of the lecture's four readings 900, 900.4, 903 and 903.3, whatever the study's sensors).
    x : float
        The true value (°C) of the draws (``belief_study``'s ``x``).
    """

    base: np.ndarray
    deltas: np.ndarray
    W: np.ndarray
    unit_k_maxdiff: float
    unit_f_maxdiff: float
    unit_fconv_maxdiff: float
    unit_f_valdiff: float
    eig_w: np.ndarray
    row_w: np.ndarray
    rowsum_maxdiff: float
    rowsum_valdiff_rms: float
    mse_eig: float
    mse_row: float
    sq_eig: np.ndarray
    sq_row: np.ndarray
    shifted: np.ndarray
    perron: Mapping[str, PerronStats]
    bin_lam: tuple[float, float]
    bin_w: np.ndarray
    x: float

    __result_spec__ = ResultSpec(
        {"base": array("n"), "deltas": array("D"), "W": array("D", "n", bounds=NONNEGATIVE), "unit_k_maxdiff": number(),
         "unit_f_maxdiff": number(), "unit_fconv_maxdiff": number(), "unit_f_valdiff": number(nonnegative=False),
         "eig_w": array("snapshots", "n", bounds=NONNEGATIVE), "row_w": array("snapshots", "n", bounds=NONNEGATIVE),
         "rowsum_maxdiff": number(),
         "rowsum_valdiff_rms": number(), "mse_eig": number(), "mse_row": number(),
         "sq_eig": array("snapshots", bounds=NONNEGATIVE),
         "sq_row": array("snapshots", bounds=NONNEGATIVE), "shifted": mask("snapshots"),
         "perron": dict_of(instance(PerronStats)),
         "bin_lam": tuple_of(number(nonnegative=False), number(nonnegative=False)),
         "bin_w": array(4, bounds=NONNEGATIVE),  # the lecture's four readings, whatever the study's n (fuzz 25 R4)
         "x": number(nonnegative=False)})
    __post_init__ = validated_post_init


@derived_inputs()
@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def belief_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    x: float = 900.0,
    seeds: tuple[int, int, int] = (2401, 2402, 2403),
    snapshots: int = 5000,
) -> BeliefStudy:
    r"""Experiment E2.4: belief-degree (Perron eigenvector) weights.

    Four parts: one draw of the sensors at ``x``, reading 1 shifted by Δ ∈ [0, 20]; the same
    readings (reading 1 +3) in °C, °F and K; eigenvector against row-sum weights
    (:func:`fusion.readings.fusion_set.row_sum_weights`) on ``snapshots`` draws, half with reading 1
    shifted by U(0, 10); the binary belief of (900, 900.4, 903, 903.3), ε = 1.

    Parameters
    ----------
    sigma : sequence of float
        Noise standard deviation of each sensor (°C).
    x : float
        True value (°C).
    seeds : (int, int, int)
        Seeds of the three random parts.
    snapshots : int
        Draws of the eigenvector against row-sum comparison (at least 2, odd or even); the even-indexed ones,
        ``ceil(snapshots / 2)``, each get their own U(0, 10) shift of reading 1.

    Returns
    -------
    BeliefStudy
        The weights against the shift Δ, the unit checks, eigenvector against row-sum weights with their MSE, and the
        Perron statistics.
    """
    sig = _sigmas(sigma, minimum=2)  # the checked array is what the study uses (fuzz 31a C4)
    n_sig = sig.size
    x = scalar(x, "x")
    seeds = [_seed(sd, "seeds") for sd in sequence(seeds, "seeds", 3)]
    snapshots = count(snapshots, "snapshots", minimum=2)
    allocation((snapshots, n_sig, n_sig), "snapshots and sigma")
    # rule 17: a dozen n x n belief matrices, eigen-decompositions and weights a snapshot, about 1.8 us an entry
    # measured (budget35: 0.57 CPU-s for 20,000 snapshots of 4 sensors, 1.2 for 2,000 of 20); without it 10**7
    # snapshots (some 260 CPU-s) were accepted
    work((snapshots, n_sig, n_sig), "snapshots and sigma", weight=180)
    # and the ~210 belief_degree calls on one n x n snapshot each (the weight curve, the examples) and the Perron
    # statistics, uncounted (fuzz 64b's class: 1,666 sensors of 2 snapshots were accepted, some 90 CPU-s): 1.3e-5 s an
    # entry and 2.9e-8 s a cube fitted to 3.98 and 11.05 CPU-s at 400 and 600 sensors (0.08 at 50; 2 snapshots,
    # time.process_time, OPENBLAS_NUM_THREADS=1, machine shared), so about twice: 2,650 units an entry, 6 a cube
    work((snapshots * 180 * n_sig**2 + 2650 * n_sig**2 + 6 * n_sig**3,), "snapshots and sigma")
    base = x + np.random.default_rng(seeds[0]).normal(size=sig.size) * sig
    deltas = np.linspace(0, 20, 201)
    e1 = np.eye(sig.size)[0]
    W = np.array([rd.belief_degree(base + d * e1).weights for d in deltas])
    snap = base + 3.0 * e1
    to_f = 1.8 * snap + 32.0
    to_k = snap + 273.15
    wc = rd.belief_degree(snap).weights
    snaps = x + np.random.default_rng(seeds[1]).normal(size=(snapshots, sig.size)) * sig
    # one independent shift for each even-indexed snapshot: ceil(snapshots / 2) draws (an odd count too)
    snaps[::2, 0] += np.random.default_rng(seeds[2]).uniform(0, 10, size=(snapshots + 1) // 2)
    eig_w = rd.fuse_epochs(snaps, "belief_degree").weights
    row_w = rd.row_sum_weights(rd.belief_matrices(snaps))
    xb = np.array([900.0, 900.4, 903.0, 903.3])
    lam_b = np.linalg.eigvalsh(rd.belief_matrix(xb, binary_eps=1.0))
    # the Perron-Frobenius claim: fuzzy belief matrices (positive) against binary ones (0/1), same snapshots
    perron: dict[str, PerronStats] = {}
    d = np.abs(snaps[:, :, None] - snaps[:, None, :])
    for kind, par in (("fuzzy", 0.25), ("fuzzy", 1.0), ("fuzzy", 4.0), ("binary", 0.5), ("binary", 1.0), ("binary", 2.0),
                      ("binary", 4.0), ("truncated", 1.0), ("truncated", 2.0), ("truncated", 4.0)):
        # truncated: the fuzzy belief (s = 1) set to 0 beyond the fusion upper limit m = par (融合上限)
        B = (np.exp(-d / (2.0 * par)) if kind == "fuzzy" else np.exp(-d / 2.0) * (d <= par) if kind == "truncated"
             else (d <= par).astype(float))
        gap = rd.perron_gap(B)
        w = rd.perron_weights(B)
        ev = np.linalg.eigvalsh(B)
        lam = ev[:, -1]
        # the claim as printed: λ > 0 of largest modulus with λA = BA for the returned A (aᵢ ≥ 0)
        res = np.linalg.norm(np.einsum("kij,kj->ki", B, w) - lam[:, None] * w, axis=1) / (lam * np.linalg.norm(w, axis=1))
        perron[f"{kind}, {'s' if kind == 'fuzzy' else 'm' if kind == 'truncated' else 'ε'} = {par:g}"] = PerronStats(
            min_gap=float(np.min(gap)), share_repeated=float(np.mean(gap <= rd.fusion_set.PERRON_RTOL)),
            min_weight=float(np.min(w)), share_zero_weight=float(np.mean(np.any(w <= ZERO_WEIGHT, axis=1))),
            min_lambda=float(np.min(lam)), lambda_is_modulus=bool(np.all(lam >= np.abs(ev[:, 0]))),
            max_residual=float(np.max(res)))
    fused_eig, fused_row = np.einsum("ij,ij->i", eig_w, snaps), np.einsum("ij,ij->i", row_w, snaps)
    shifted = np.zeros(snapshots, dtype=bool)
    shifted[::2] = True
    return BeliefStudy(
        base=base, deltas=deltas, W=W,
        unit_k_maxdiff=float(np.max(np.abs(rd.belief_degree(to_k).weights - wc))),
        unit_f_maxdiff=float(np.max(np.abs(rd.belief_degree(to_f).weights - wc))),
        unit_fconv_maxdiff=float(np.max(np.abs(rd.belief_degree(to_f, scale=1.8).weights - wc))),
        unit_f_valdiff=float((rd.belief_degree(to_f).value - 32) / 1.8 - rd.belief_degree(snap).value),
        eig_w=eig_w, row_w=row_w,
        rowsum_maxdiff=float(np.max(np.abs(eig_w - row_w))),
        rowsum_valdiff_rms=float(np.sqrt(np.mean(np.einsum("ij,ij->i", eig_w - row_w, snaps) ** 2))),
        mse_eig=float(np.mean((fused_eig - x) ** 2)),
        mse_row=float(np.mean((fused_row - x) ** 2)),
        sq_eig=(fused_eig - x) ** 2, sq_row=(fused_row - x) ** 2, shifted=shifted, perron=perron,
        bin_lam=(float(lam_b[-1]), float(lam_b[-2])),
        bin_w=rd.belief_degree(xb, binary_eps=1.0).weights, x=float(x),
    )


class BeliefKind(StrEnum):
    """Method keys of the belief fusions of :func:`belief_parameter_study` (labels: :data:`fusion.book.style.METHOD_LABELS`).

    Attributes
    ----------
    FUZZY
        The fuzzy exponential belief, its Perron vector (scale s varied).
    BINARY
        The binary belief through its Perron vector (threshold ε varied).
    DELETION, DELETION_THIRD, DELETION_ALL
        The lecture's deletion rule (:func:`fusion.readings.fusion_set.binary_deletion`): a reading kept when at
        least half, a third or all of the others trust it (:data:`DELETION_SUPPORT`; ε varied).
    FUZZY_LIMIT
        The fuzzy belief truncated at the fusion upper limit m (融合上限; m varied).
    """

    FUZZY = "lec_bel_fuzzy"
    BINARY = "lec_bel_binary"
    DELETION = "lec_bel_deletion"
    DELETION_THIRD = "lec_bel_deletion_third"
    DELETION_ALL = "lec_bel_deletion_all"
    FUZZY_LIMIT = "lec_bel_fuzzy_limit"


#: Kinds of belief fusion of :func:`belief_parameter_study` and the analyst's parameter each varies.
BELIEF_KINDS: dict[BeliefKind, str] = constant({BeliefKind.FUZZY: "scale s", BeliefKind.BINARY: "threshold ε",
                                       BeliefKind.DELETION: "threshold ε", BeliefKind.DELETION_THIRD: "threshold ε",
                                       BeliefKind.DELETION_ALL: "threshold ε",
                                       BeliefKind.FUZZY_LIMIT: "fusion upper limit m (融合上限)"})

#: ``min_support`` of each deletion kind of :data:`BELIEF_KINDS` (:func:`fusion.readings.fusion_set.binary_deletion`):
#: the share of the other readings that must trust a reading for it to be kept.
DELETION_SUPPORT: dict[BeliefKind, float] = constant({BeliefKind.DELETION: 0.5, BeliefKind.DELETION_THIRD: 1.0 / 3.0,
                                             BeliefKind.DELETION_ALL: 1.0})


@dataclass(frozen=True)
class BeliefParameterStudy:
    """Experiment E2.4b: how much the fused value depends on the analyst's parameter (:func:`belief_parameter_study`).

    Attributes
    ----------
    fused : mapping of BeliefKind to ndarray
        ``fused[kind]``, shape (snapshots, len(params)), for every kind of :data:`BELIEF_KINDS`.
    sq : mapping of BeliefKind to ndarray
        Squared errors, same keys and shapes.
    sq_mean : ndarray, shape (snapshots,)
        Squared error of the arithmetic mean.
    params, grid : ndarray
        The parameter values run and the grid the spread is taken over.
    spread : mapping of BeliefKind to ndarray
        ``spread[kind]``, shape (snapshots,): max − min of the fused value over ``grid``.
    seed, snapshots : int
    x, shift, limit_scale : float
        The parameters of :func:`belief_parameter_study`.
    """

    fused: Mapping[BeliefKind, np.ndarray]
    sq: Mapping[BeliefKind, np.ndarray]
    sq_mean: np.ndarray
    params: np.ndarray
    grid: np.ndarray
    spread: Mapping[BeliefKind, np.ndarray]
    seed: int
    snapshots: int
    x: float
    shift: float
    limit_scale: float

    __result_spec__ = ResultSpec(
        {"fused": arrays(tuple(BELIEF_KINDS), "snapshots", "params"), "sq": arrays(tuple(BELIEF_KINDS), "snapshots", "params"),
         "sq_mean": array("snapshots"), "params": array("params"), "grid": array("grid"),
         "spread": arrays(tuple(BELIEF_KINDS), "snapshots"), "x": number(nonnegative=False), "shift": number(),
         "limit_scale": number(positive=True)},
        relations=(lambda v, cls: _grid_of_params(v, cls),))

    def __post_init__(self) -> None:
        """Every field checked (``fusion._results``): a ValueError naming the field, e.g. ``BeliefParameterStudy.grid``."""
        store_read(self, "seed", _seed(self.seed, "BeliefParameterStudy.seed"))  # a plain int (rule 20)
        snapshots = count(self.snapshots, "BeliefParameterStudy.snapshots", minimum=2)
        store_read(self, "snapshots", snapshots)  # the plain int read, never a caller's __index__ object (fuzz 31b C7)
        validated_post_init(self)
        if self.sq_mean.size != snapshots:
            raise ValueError(f"BeliefParameterStudy.snapshots ({snapshots}) must be the number of rows of its arrays "
                             f"({self.sq_mean.size})")


@derived_inputs()
def belief_parameter_study(
    sigma: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    x: float = 900.0,
    params: Sequence[float] = (0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0),
    snapshots: int = 200,
    shift: float = 10.0,
    seed: int = 2404,
    grid: Sequence[float] = (0.5, 1.0, 2.0, 4.0),
    limit_scale: float = 1.0,
) -> BeliefParameterStudy:
    r"""Experiment E2.4b: the fused value's dependence on the analyst's parameter, fuzzy against binary belief.

    The lecture rejects the binary belief (:math:`b_{ij} = 1` if :math:`|x_i - x_j| \le m_{ij}`, its
    "fusion upper limit" m, here ε) with its deletion rule as "too much influenced by subjective
    factors", and proposes the fuzzy exponential belief. Each needs a parameter in the readings' unit:
    the threshold ε, the scale s. On ``snapshots`` draws of the sensors at ``x`` (reading 1 shifted by
    U(0, ``shift``) in every other draw), each snapshot is fused with every value of ``params`` as s
    (fuzzy belief, Perron vector), as ε (the lecture's deletion rule,
    :func:`fusion.readings.fusion_set.binary_deletion`, with a reading kept when at least half, a third
    or all of the others trust it, :data:`DELETION_SUPPORT`; and the binary belief through its Perron
    vector, the book's construction), and as m, the fusion upper limit (融合上限): the fuzzy belief
    with scale ``limit_scale`` truncated to 0 beyond m. The spread of a snapshot's fused values over a
    grid of values measures how much the analyst's choice moves the result (:func:`belief_spread`); the
    squared errors and those of the arithmetic mean (``sq_mean``) say whether the rule does better than
    the plain average on that grid at all.

    Parameters
    ----------
    sigma : sequence of float
        Noise SDs of the sensors.
    x : float
        True value.
    params : sequence of float
        Every value of s, ε and m run (readings' unit), positive, no two equal (the spread is keyed by value) nor
        alike to 6 significant digits (the chapter's table labels a column ``f"{p:g}"``).
    snapshots : int
        Number of draws.
    shift : float
        Upper end of the uniform shift of reading 1 (every other draw).
    seed : int
    grid : sequence of float
        The primary grid (a subset of ``params``) of ``spread``.
    limit_scale : float
        Scale s of the truncated fuzzy belief.

    Returns
    -------
    BeliefParameterStudy
        The fused values of fuzzy and binary belief per parameter and snapshot, their squared errors and the spread over
        ``grid``.
    """
    sig = _sigmas(sigma, minimum=2)
    x = scalar(x, "x")
    vals = _values(params, "params")
    if np.any(vals <= 0):
        raise ValueError("params must be positive")
    g = _values(grid, "grid")
    snapshots = count(snapshots, "snapshots", minimum=2)
    # rule 17: a fusion per param (and per snapshot and deletion support) of sensors² belief degrees, two LOOP_STEPs
    # each (fix39a: one gave 19.8-20.5 CPU-s at the edge, 163,934 snapshots, measured at 1/20 and 1/5); by the number
    # of params before their repeats are looked for
    # (fix70a, fuzz 62b's class: each entry hashed before a budget that needs only their number, 2.5 CPU-s a 10**7 list)
    loop_work((vals.size, 3 + snapshots * len(DELETION_SUPPORT)), sig.size**2, "params and snapshots",
              step=2 * LOOP_STEP)
    if g.size > vals.size or not set(g.tolist()) <= set(vals.tolist()):  # after the budget (fuzz 64b's class)
        raise ValueError(f"grid must be a subset of params, got {shown(tuple(g.tolist()))}")
    distinct(vals.tolist(), "params"), distinct(g.tolist(), "grid")  # the spread is keyed by the params' values
    distinct_printed(vals.tolist(), "params", general, "labels a column")  # the chapter's f"{p:g}" (fuzz 30b)
    shift = scalar(shift, "shift", lo=0.0)
    seed = _seed(seed)
    ls = scalar(limit_scale, "limit_scale", lo=0.0, lo_open=True)
    rng = np.random.default_rng(seed)
    snaps = x + rng.normal(size=(snapshots, sig.size)) * sig
    snaps[::2, 0] += rng.uniform(0, shift, size=(snapshots + 1) // 2)
    fused = {
        BeliefKind.FUZZY: np.column_stack([rd.fuse_epochs(snaps, "belief_degree", scale=float(p)).values for p in vals]),
        BeliefKind.BINARY: np.column_stack([rd.fuse_epochs(snaps, "belief_degree", binary_eps=float(p)).values
                                            for p in vals]),
        **{kind: np.array([[rd.binary_deletion(r, float(p), min_support=q).value for p in vals] for r in snaps])
           for kind, q in DELETION_SUPPORT.items()},
        BeliefKind.FUZZY_LIMIT: np.column_stack([rd.fuse_epochs(snaps, "belief_degree", scale=ls, limit=float(p)).values
                                                 for p in vals]),
    }
    # computed here from validated arguments: the private constructor
    return trusted(BeliefParameterStudy, fused=fused, sq={k: (v - x) ** 2 for k, v in fused.items()},
                   sq_mean=(snaps.mean(axis=1) - x) ** 2, params=vals.copy(), grid=g.copy(),
                   spread={k: _spread(v, vals, g) for k, v in fused.items()}, seed=seed,
                   snapshots=snapshots, x=float(x), shift=float(shift), limit_scale=float(ls))


def _grid_of_params(v: dict, cls: str) -> None:
    """The study's parameter values are positive, its grid a subset of them, and ``spread`` the spread over it."""
    params, grid = v["params"], v["grid"]
    if np.any(params <= 0):
        raise ValueError(f"{cls}.params must be positive")
    if not set(grid.tolist()) <= set(params.tolist()):
        raise ValueError(f"{cls}.grid must be a subset of {cls}.params")
    for k, fused in v["fused"].items():
        if not np.array_equal(v["spread"][k], _spread(fused, params, grid)):
            raise ValueError(f"{cls}.spread[{shown(str(k))}] must be the spread of {cls}.fused[{shown(str(k))}] over {cls}.grid")


def _spread(fused: np.ndarray, params: np.ndarray, values: np.ndarray) -> np.ndarray:
    """Per-row max − min of ``fused`` (rows, len(params)) over the columns of ``values`` (each one of ``params``)."""
    plist = list(params)
    missing = [float(p) for p in values if float(p) not in plist]
    if missing:
        raise ValueError(f"values must be among the study's params, got {missing}")
    idx = [plist.index(float(p)) for p in values]
    return np.ptp(fused[:, idx], axis=1)


def belief_spread(s: BeliefParameterStudy, kind: BeliefKind, values: ArrayLike) -> np.ndarray:
    r"""Per-snapshot spread (max − min) of the fused value over some of the parameter values of E2.4b.

    Parameters
    ----------
    s : BeliefParameterStudy
        Output of :func:`belief_parameter_study`.
    kind : BeliefKind
        One of :data:`BELIEF_KINDS`.
    values : array_like
        Parameter values, each one of ``s.params`` (at least one).

    Returns
    -------
    ndarray, shape (snapshots,)
        Spread of each snapshot's fused value (readings' unit).
    """
    instance_of(s, BeliefParameterStudy, "s")
    kind = one_of(kind, tuple(BELIEF_KINDS), "kind")
    return _spread(s.fused[kind], s.params, _values(values, "values"))
