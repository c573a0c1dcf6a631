"""Chapter 01 (the optimal fusion set): the Monte-Carlo studies the records use.

Each is cached per (seed, runs); the shares of the set's members are computed on their draws.
"""

from __future__ import annotations

import inspect

from fusion._guards import own_underflow
from fusion._validation import instance_of, read_mapping

from collections.abc import Mapping
from dataclasses import dataclass
from fusion._counts import seed as check_seed
from fusion.book.study_cache import study_cache

import numpy as np

from fusion import data
from fusion import readings as rd
from fusion._results import ResultSpec, array, dict_of, number, tuple_of, validated_post_init
from fusion._validation import FloatArray, flag, one_of, scalar
from fusion._shown import shown
from fusion.book.chapters import ofs_fair
from fusion.book.ledger import Comparison, Conjunction
from fusion.book.tables import rounded
from fusion.scenarios import thermocouples
from fusion.scenarios.thermocouples import PairedStudy
from fusion.book.chapters.ofs.readings import FAMILIES, alpha_methods, family_mae, weight_ablation
from fusion.book.chapters.ofs.settings import METHODS, NOISE, FailureCase, _noise_key
from fusion.book.glue import GlueValues
from fusion._docstrings import ParameterDocs
from fusion._counts import allocation, count
from fusion._limits import MAX_WORK, MEMBERSHIP_STUDY, STUDY_WORK, recorded_as, work
from fusion.book._study_budget import studies_first

__all__ = [
    "FaultyMembership",
    "faulty_member_share",
    "healthy_dropped_share",
    "support_bound_check",
    "closing_numbers",
    "not_neighbourhood_share",
    "SCALES",
    "study",
    "fair_weights",
    "alpha_study",
    "MembershipStudy",
    "membership_study",
    "fair",
    "WeightStudy",
    "weight_study",
]

#: Samples and sensors of the chapter's draws (``thermocouples.simulate``'s defaults): a run is one such array.
_RUN_SHAPE = (100, 10)


def _runs(runs: object) -> int:
    """``runs`` as a count, refused by name when its draws (``runs`` x 100 samples x 10 sensors) are beyond the memory
    budget (fuzz 26d W4): the studies' callees (``thermocouples.simulate``, ``paired_study``) would name their own
    arguments (``n_runs, n_samples and n_sensors``), not this module's ``runs``."""
    runs = count(runs, "runs")
    allocation((runs, *_RUN_SHAPE), "runs")
    return runs


#: The one method these studies fuse their own draws with (``fuse_epochs``).
_OFS = ({"method": "optimal_fusion_set"},)
#: The samples 50-80 of the failure window, the epochs fused by the studies of the failure.
_WINDOW_EPOCHS = 31


def _fused_runs(runs: object, fused: tuple[tuple[int, int], ...] = ((_RUN_SHAPE[0], 1),), sweeps: int = 0,
                limit: int = MAX_WORK, served: str | None = None) -> int:
    """``runs`` of a study that draws ``runs`` runs and fuses them itself, refused by name before the draws when
    what it runs together is beyond a budget (fuzz 54a C2: only the draws' memory was checked, so ``runs`` up to
    268,435 drew and ran for 8-11 CPU-s before ``fuse_epochs``' input budget, at most 33,554 runs of 100 epochs,
    refused naming ``x`` or ``z``).

    Counted by the callees' own budget functions, summed (``fusion.book._study_budget.studies_first``): the draws at
    ``thermocouples``' ``_PAIRED_READING`` units a reading; per ``(epochs, passes)`` of ``fused``, ``passes``
    ``fuse_epochs`` of ``runs x epochs`` epochs of 10 readings (``thermocouples._methods_work``: its input and kernel
    limits, ``epochs_limit``, and its measured units); ``sweeps`` ``scale_sweep`` calls of :data:`SCALES`
    (their own ``_scale_sweep_work``); the sum within ``limit`` (``served``: its ``STUDY_WORK`` key)."""
    runs = _runs(runs)
    n = _RUN_SHAPE[1]
    parts = [lambda: work((runs, *_RUN_SHAPE), "runs", weight=thermocouples._PAIRED_READING)]
    parts += [lambda e=e, k=k: thermocouples._methods_work(runs * e, n, _OFS, "runs", fusions=k) for e, k in fused]
    parts += [lambda: thermocouples._scale_sweep_work(len(SCALES), runs, "runs")] * sweeps
    studies_first(parts, "runs", limit, served)
    return runs


#: The parameters of this module's studies, documented once.
_PARAMS = ParameterDocs({"seed, runs": "int\n    As in :func:`study` (the same seed gives the same draws).",
                         "noise": "str\n    A key of :data:`NOISE`, given as text (a TypeError naming ``noise`` "
                                  "otherwise, a ValueError for another text)."})
#: The parameters of the fair study's two entries, :func:`fair` and :func:`fair_weights`.
_FAIR_PARAMS = ParameterDocs({"seed": "int\n    The seed of the fair study's draws.",
                              "runs": "int\n    Runs of 100 samples per sweep point."})


def study(seed: int, runs: int, noise: str = "unequal", failure: str = "fixed", include_self: bool = True) -> PairedStudy:
    """The paired study of the three methods (:func:`fusion.scenarios.thermocouples.paired_study`), cached.

    Parameters
    ----------
    seed, runs : int
        The seed of the draws and the number of runs.
    noise : str
        A key of :data:`NOISE`, given as text (a TypeError naming ``noise`` otherwise, a ValueError for another text).
    failure : str
        One of :data:`fusion.scenarios.thermocouples.FAILURE_MODES` (the readings of "randomly").
    include_self : bool
        Whether eq. 9's sum over j includes j = i (the package's default, True); False fuses the optimal set
        and the mean only (the reading of eq. 9 without j = i).

    Returns
    -------
    PairedStudy
        The absolute errors (°C) of every method per run and sample, without and with the failure, on the same draws.
    """
    seed = check_seed(seed)
    runs = _runs(runs)
    failure = one_of(failure, thermocouples.FAILURE_MODES, "failure")
    return _study(seed, runs, _noise_key(noise), failure, flag(include_self, "include_self"))


@study_cache(maxsize=16)
def _study(seed: int, runs: int, noise: str, failure: str, include_self: bool = True) -> PairedStudy:
    # the geometric spreads and eq. 9 without j = i are readings of the records against the mean only
    methods = METHODS if noise in ("unequal", "equal") and include_self else {k: METHODS[k] for k in
                                                                                ("optimal_fusion_set", "mean")}
    if not include_self:
        methods = {**methods, "optimal_fusion_set": {"method": "optimal_fusion_set", "include_self": False}}
    return thermocouples.paired_study(seed, runs, methods, sigma=NOISE[noise], failure_mode=failure)


@_PARAMS("seed, runs")
def alpha_study(seed: int, runs: int) -> PairedStudy:
    """The primary draws fused by the support degree at every α of :data:`ALPHAS` (cached).

    Returns
    -------
    PairedStudy
        One method per α (:func:`~fusion.book.chapters.ofs.alpha_methods`), on the draws of :func:`study` at the same seed.
    """
    seed = check_seed(seed)
    runs = _runs(runs)
    return _alpha_study(seed, runs)


@study_cache(maxsize=4)
def _alpha_study(seed: int, runs: int) -> PairedStudy:
    return thermocouples.paired_study(seed, runs, alpha_methods())


@dataclass(frozen=True)
class MembershipStudy:
    """The membership-function study on the primary draws: scales of eq. 6, families, equal weights.

    Attributes
    ----------
    scales : ndarray, shape (k,)
        Scales of eq. 6 (°C); the source's factor 1/2 is 2 °C.
    sweep : dict
        :class:`~fusion.book.chapters.ofs.FailureCase` -> per-run MAE of each scale, shape (k, runs)
        (samples 50-80 under failure).
    family : dict
        :class:`~fusion.book.chapters.ofs.FailureCase` -> :func:`family_mae`.
    ablation : dict
        :class:`~fusion.book.chapters.ofs.FailureCase` -> :func:`weight_ablation`.
    """

    scales: FloatArray
    sweep: Mapping[FailureCase, FloatArray]
    family: Mapping[FailureCase, Mapping[str, FloatArray]]
    ablation: Mapping[FailureCase, Mapping[str, FloatArray]]

    __result_spec__ = ResultSpec(
        {"scales": array("k", increasing=True, bounds=(0.0, np.inf)),
         "sweep": dict_of(array("k", "runs", bounds=(0.0, np.inf)), keys=tuple(FailureCase)),
         "family": dict_of(dict_of(array("runs", bounds=(0.0, np.inf))), keys=tuple(FailureCase)),
         "ablation": dict_of(dict_of(array("runs", bounds=(0.0, np.inf)), keys=("optimal_fusion_set", "uniform_set")),
                             keys=tuple(FailureCase))})
    __post_init__ = validated_post_init



#: Scales of eq. 6 swept (°C).
SCALES: tuple[float, ...] = (0.125, 0.25, 0.5, 1.0, 2.0, 4.0, 8.0, 16.0, 32.0)


@_PARAMS("seed, runs")
def membership_study(seed: int, runs: int) -> MembershipStudy:
    """Scale sweep, membership families and the equal-weight ablation on the primary draws (cached).

    Returns
    -------
    MembershipStudy
        Without and with the failure: the MAE by scale, by family and with equal weights.
    """
    seed = check_seed(seed)
    # the ablation's and each family's fuse_epochs (family_values fuses once a family), with and without the failure
    fusions = 1 + len(FAMILIES)
    runs = _fused_runs(runs, ((_RUN_SHAPE[0], fusions), (_WINDOW_EPOCHS, fusions)), sweeps=2,
                       limit=STUDY_WORK[MEMBERSHIP_STUDY], served=MEMBERSHIP_STUDY)
    return _membership_study(seed, runs)


@study_cache(maxsize=4)
def _membership_study(seed: int, runs: int) -> MembershipStudy:
    seed = check_seed(seed)   # an integer seed (rule 11), named
    sc = np.array(SCALES)
    z = thermocouples.simulate(np.random.default_rng(seed), n_runs=runs)
    zf = thermocouples.inject_failure(z, **data.YANG2012_FAILURE)
    return MembershipStudy(
        scales=sc,
        sweep={FailureCase.NONE: thermocouples.scale_sweep(seed, runs, sc),
               FailureCase.FAILURE: thermocouples.scale_sweep(seed, runs, sc, failure={}, window=(50, 80))},
        family={FailureCase.NONE: family_mae(z), FailureCase.FAILURE: family_mae(zf, window=(50, 80))},
        ablation={FailureCase.NONE: weight_ablation(z), FailureCase.FAILURE: weight_ablation(zf, window=(50, 80))})


@_FAIR_PARAMS("seed", "runs")
def fair(seed: int, runs: int = 100) -> ofs_fair.FairStudy:
    """:func:`fusion.book.chapters.ofs_fair.fair_study` with its default sweeps (cached).

    Returns
    -------
    FairStudy
        (sweep, value) -> method -> per-run mean absolute error (°C), over the default sweeps.
    """
    seed = check_seed(seed)
    runs = _runs(runs)
    ofs_fair._budget((runs, *_RUN_SHAPE), sum(_FAIR_POINTS.values()), ofs_fair.FAIR_METHODS, ("runs", "runs"))
    return _fair(seed, runs)


@study_cache(maxsize=4)
def _fair(seed: int, runs: int) -> ofs_fair.FairStudy:
    return ofs_fair.fair_study(seed, n_runs=runs)


#: The points of :func:`fair`'s default sweeps, by sweep argument of ``ofs_fair.fair_study`` (its work budget).
_FAIR_POINTS = {k: len(inspect.signature(ofs_fair.fair_study).parameters[k].default)
                for k in ("sizes", "counts", "spreads", "opposite")}

#: The methods the ledger's fair-study readings compare (``ev_weights_reasonable``): eqs. 6-11's weights and equal weights.
_WEIGHT_METHODS = ("optimal_fusion_set", "uniform_set")


@_FAIR_PARAMS("seed", "runs")
def fair_weights(seed: int, runs: int = 100) -> ofs_fair.FairStudy:
    """:func:`fair` with only the two methods the ledger's readings compare and without the opposite-sign sweep (cached).

    The draws are :func:`fair`'s, so every array is the one :func:`fair` gives for those methods and sweep
    points, bit for bit (``tests/test_ofs_chapter.py``), at a fifth of the work: the ledger reads the fair study
    at the chapter's run count, five times the notebook's.

    Returns
    -------
    FairStudy
        Only ``"optimal_fusion_set"`` and ``"uniform_set"``, at the fault-size, fault-count and spread sweeps.
    """
    seed = check_seed(seed)
    runs = _runs(runs)
    ofs_fair._budget((runs, *_RUN_SHAPE), sum(_FAIR_POINTS.values()) - _FAIR_POINTS["opposite"], _WEIGHT_METHODS,
                     ("runs", "runs"))
    return _fair_weights(seed, runs)


@study_cache(maxsize=4)
def _fair_weights(seed: int, runs: int) -> ofs_fair.FairStudy:
    return ofs_fair.fair_study(seed, n_runs=runs, opposite=(), methods=_WEIGHT_METHODS)


@dataclass(frozen=True)
class WeightStudy:
    """How the weights of eqs. 8-11 treat each sensor of the primary draws, without failure.

    Attributes
    ----------
    relative : ndarray, shape (runs, n_sensors)
        Per run, each sensor's weight relative to an equal share of its set (weight × set size; 1 = equal
        weights), averaged over the epochs at which it is a member.
    member : ndarray, shape (n_sensors,)
        Share of all epochs at which each sensor is a member of the set.
    """

    relative: FloatArray
    member: FloatArray

    __result_spec__ = ResultSpec({"relative": array("runs", "sensors", bounds=(0.0, np.inf)),
                                  "member": array("sensors", bounds=(0.0, 1.0))})
    __post_init__ = validated_post_init


@_PARAMS("seed, runs")
def weight_study(seed: int, runs: int, include_self: bool = True) -> WeightStudy:
    """:class:`WeightStudy` of the primary draws (unequal noise, no failure), cached.

    Parameters
    ----------
    include_self : bool
        Whether eq. 9's sum includes j = i (as in :func:`study`).

    Returns
    -------
    WeightStudy
        Per run and sensor the weight relative to an equal share of its set, and each sensor's share of epochs as a
        member.
    """
    seed = check_seed(seed)
    runs = _fused_runs(runs)
    return _weight_study(seed, runs, flag(include_self, "include_self"))


@study_cache(maxsize=4)
def _weight_study(seed: int, runs: int, include_self: bool = True) -> WeightStudy:
    seed = check_seed(seed)   # an integer seed (rule 11), named
    z = thermocouples.simulate(np.random.default_rng(seed), n_runs=runs)
    f = rd.fuse_epochs(z.reshape(-1, z.shape[-1]), "optimal_fusion_set", include_self=include_self)
    w, m = f.weights.reshape(z.shape), f.members.reshape(z.shape)
    rel = np.where(m, w * m.sum(axis=2, keepdims=True), 0.0).sum(axis=1) / np.maximum(m.sum(axis=1), 1)
    return WeightStudy(relative=rel, member=m.mean(axis=(0, 1)))


@study_cache(maxsize=8)
@_PARAMS("seed, runs", "noise")
def not_neighbourhood_share(seed: int, runs: int, noise: str = "unequal") -> float:
    """Share of the epochs, without failure, at which the set is no neighbourhood set of the true value 900 °C.

    The set of eq. 5 is the set of the readings within some neighbourhood of X (Definition 3) only if every kept
    reading is closer to X than every dropped one; at the other epochs no neighbourhood width, however chosen,
    gives the set. The draws are those of :func:`study` (same seed).

    Returns
    -------
    float
        The fraction, in [0, 1], of all epochs at which a dropped reading lies nearer 900 °C than a kept one.
    """
    seed = check_seed(seed)
    runs = _fused_runs(runs)
    rng = np.random.default_rng(seed)
    z = thermocouples.simulate(rng, sigma=NOISE[_noise_key(noise)], n_runs=runs).reshape(-1, 10)
    m = rd.fuse_epochs(z, "optimal_fusion_set").members
    dist = np.abs(z - 900.0)
    kept_far = np.where(m, dist, -np.inf).max(axis=1)
    dropped_near = np.where(~m, dist, np.inf).min(axis=1)
    return float(np.mean(dropped_near < kept_far))


@dataclass(frozen=True)
class FaultyMembership:
    """How often the two failing sensors (4 and 10) are members of the set at the epochs 50-80.

    Attributes
    ----------
    share : tuple of float
        Per failing sensor, the member share over its faulty epochs (0 when it has none).
    all_epochs : tuple of float
        Per failing sensor, the member share over all epochs 50-80.
    faulty : tuple of float
        Per failing sensor, the share of the epochs 50-80 at which its reading is faulty.
    """

    share: tuple[float, float]
    all_epochs: tuple[float, float]
    faulty: tuple[float, float]

    __result_spec__ = ResultSpec({name: tuple_of(number(bounds=(0.0, 1.0)), count=2)
                                  for name in ("share", "all_epochs", "faulty")})
    __post_init__ = validated_post_init


@_PARAMS("seed, runs", "noise")
def faulty_member_share(seed: int, runs: int, noise: str = "unequal", failure: str = "fixed") -> FaultyMembership:
    """Share of the epochs 50-80 at which each failing sensor is a member of the set, at its *faulty* epochs.

    A failing sensor's reading counts as faulty at an epoch when the bias added to it there exceeds twice its
    noise σ (under "fixed" every epoch 50-80; under the random readings of 随机地 only some: a random bias can be
    zero or tiny, and keeping such a reading is correct). The draws are those of :func:`study` (same seed).

    Parameters
    ----------
    failure : str
        One of :data:`fusion.scenarios.thermocouples.FAILURE_MODES`.

    Returns
    -------
    FaultyMembership
        Per failing sensor (4, 10): the member share over its faulty epochs, over all epochs 50-80, and the
        share of the epochs 50-80 that are faulty.
    """
    seed = check_seed(seed)
    runs = _fused_runs(runs, ((_WINDOW_EPOCHS, 1),))
    failure = one_of(failure, thermocouples.FAILURE_MODES, "failure")
    sig = np.broadcast_to(np.asarray(NOISE[_noise_key(noise)], float), (10,))
    rng = np.random.default_rng(seed)
    z = thermocouples.simulate(rng, sigma=NOISE[_noise_key(noise)], n_runs=runs)
    zf = thermocouples.random_failure(z, rng, str(failure))
    cols = np.array([3, 9])
    win = zf[:, 49:80]
    m = rd.fuse_epochs(win.reshape(-1, 10), "optimal_fusion_set").members.reshape(win.shape)[..., cols]
    faulty = np.abs(zf - z)[:, 49:80][..., cols] > 2.0 * sig[cols]
    share = [float(m[..., k][faulty[..., k]].mean()) if faulty[..., k].any() else 0.0 for k in range(2)]
    return FaultyMembership(share=(share[0], share[1]), all_epochs=(float(m[..., 0].mean()), float(m[..., 1].mean())),
                            faulty=(float(faulty[..., 0].mean()), float(faulty[..., 1].mean())))


#: The (record id, reading key) evidence that :func:`closing_numbers` reads from ``judged``, with its types: the
#: paired comparisons whose runs it reads, and the scale reading (a conjunction of the scales) whose status it reads.
_CLOSING_READINGS: dict[tuple[str, str], tuple[type, ...]] = {
    ("yang-fig4-unaffected", "equal-noise"): (Comparison,), ("yang-weights-reasonable", "primary"): (Comparison,),
    ("yang-weights-reasonable", "failure"): (Comparison,), ("yang-membership-free", "scale"): (Comparison, Conjunction)}


def _closing_studies(study_hs: PairedStudy, study_eq: PairedStudy) -> None:
    """The roles of :func:`closing_numbers`' studies by the noise levels they record (issue 35, swaps): ``study_hs``
    at the primary levels (``NOISE["unequal"]``), ``study_eq`` at one level for every sensor. Their values are
    glued side by side, not paired, so their seeds and runs may differ. A study that records no noise (``sigma``
    None: built by hand) is not checked."""
    primary = np.broadcast_to(np.asarray(NOISE["unequal"], dtype=float), (10,))
    if study_hs.sigma is not None and (study_hs.sigma.shape != primary.shape or not recorded_as(primary,
                                                                                                study_hs.sigma)):
        raise ValueError("study_hs must be the study at the primary (unequal) noise levels, NOISE['unequal'], got one "
                         "at other levels (study_hs and study_eq swapped, or another noise's study?)")
    if study_eq.sigma is not None and np.ptp(study_eq.sigma) > 0.0:
        raise ValueError("study_eq must be the study with equal noise (one level for every sensor), got one at "
                         "unequal levels (study_hs and study_eq swapped, or another noise's study?)")


def closing_numbers(study_hs: PairedStudy, study_eq: PairedStudy, weights: object,
                    judged: Mapping[tuple[str, str], Comparison], relative_margin: float) -> GlueValues:
    """The glue values of the chapter's verdict paragraphs that are not records' numbers (chapter bookkeeping).

    Parameters
    ----------
    study_hs, study_eq : PairedStudy
        The failure study with the primary (unequal) noise levels and with equal noise: each is checked by the
        noise levels it records (``sigma``), so the two swapped, one twice or another noise's study are refused (a
        study that records none, built by hand, is not checked).
    weights : WeightStudy
        :func:`weight_study` at the chapter's seed and runs (its ``member`` shares).
    judged : mapping
        (record id, reading key) → the reading's comparison with the claim file's margin applied.
    relative_margin : float
        The claim file's margin of the MAE quantity.

    Returns
    -------
    GlueValues
        Glue key → value (rounded as the prose prints them).

    Raises
    ------
    TypeError
        A study not a PairedStudy, ``weights`` not a :class:`WeightStudy`, ``judged`` not a mapping, a comparison
        it must hold not a :class:`~fusion.book.ledger.Comparison` (the scale reading: a comparison or a
        :class:`~fusion.book.ledger.Conjunction`).
    ValueError
        ``judged`` lacking a (record, reading) the paragraphs quote, a study lacking
        the two failing sensors' shares or a method of :data:`METHODS`, or ``relative_margin`` not a finite
        number in [0, 1]; a study at the other role's noise levels (or at levels of neither role).
    """
    for name, st in (("study_hs", study_hs), ("study_eq", study_eq)):
        instance_of(st, PairedStudy, name)
        lacking = [m for m in METHODS if m not in st.clean]
        if lacking or len(st.failed_member_share) != 2:
            raise ValueError(f"{name} must be a study of the three METHODS under the chapter's failure (two failing "
                             f"sensors), got the methods {list(st.clean)} and {len(st.failed_member_share)} shares")
    instance_of(weights, WeightStudy, "weights")
    judged = read_mapping(judged, "judged")   # read once: the readings checked are the ones glued (decision 31a C2)
    instance_of(judged, Mapping, "judged")
    lacking = [k for k in _CLOSING_READINGS if k not in judged]
    if lacking:
        raise ValueError(f"judged lacks the (record, reading) keys {lacking} that the closing paragraphs quote")
    for k, types in _CLOSING_READINGS.items():
        instance_of(judged[k], types, f"judged[{shown(k)}]")
    relative_margin = scalar(relative_margin, "relative_margin", lo=0.0, hi=1.0)
    _closing_studies(study_hs, study_eq)
    unaff = judged[("yang-fig4-unaffected", "equal-noise")]
    return {"ofs_margin": relative_margin,
            "ofs_member_s1": rounded(weights.member[0], 3), "ofs_member_s10": rounded(weights.member[-1], 3),
            "ofs_fig4_unaffected_eq_status": unaff.status(),
            **{f"ofs_abl_uni_{k}_rel": rounded(float(np.mean(c.b)) / float(np.mean(c.a)) - 1, 4)
               for k, c in (("clean", judged[("yang-weights-reasonable", "primary")]),
                            ("fail", judged[("yang-weights-reasonable", "failure")]))},
            "ofs_abl_fail_won": int(np.sum(np.asarray(judged[("yang-weights-reasonable", "failure")].a)
                                           < np.asarray(judged[("yang-weights-reasonable", "failure")].b))),
            "ofs_scale_all_equiv": judged[("yang-membership-free", "scale")].status() == "reproduced",
            "ofs_keep_hs": rounded(study_hs.set_size.mean(), 2), "ofs_keep_eq": rounded(study_eq.set_size.mean(), 2),
            "ofs_member4_hs": rounded(study_hs.failed_member_share[0], 3),
            "ofs_member10_hs": rounded(study_hs.failed_member_share[1], 3),
            "ofs_member4_eq": rounded(study_eq.failed_member_share[0], 3),
            "ofs_whole_eq_ofs": rounded(study_eq.mae("optimal_fusion_set", True, window=False).mean()),
            "ofs_whole_eq_sup": rounded(study_eq.mae("support_degree", True, window=False).mean())}


# --------------------------------------------------------------------------- open points of the 2026-12-05 review
@_PARAMS("seed, runs", "noise")
def healthy_dropped_share(seed: int, runs: int, noise: str = "unequal") -> dict[str, float]:
    """Share of the healthy sensors' readings the set drops at the epochs 50-80, with and without the failure.

    The draws are those of :func:`faulty_member_share` under the "fixed" failure (same seed): sensors 4 and 10
    are biased by +4 and +8 °C at samples 50-80, the other eight are healthy. The same epochs without the
    failure give the rate at which the set drops valid readings anyway.

    Returns
    -------
    dict
        ``"failure"``, ``"clean"``: share of the eight healthy sensors' readings outside the set over the
        epochs 50-80; ``"epochs"``: number of epochs judged.
    """
    seed = check_seed(seed)
    runs = _fused_runs(runs, ((_WINDOW_EPOCHS, 2),))
    rng = np.random.default_rng(seed)
    z = thermocouples.simulate(rng, sigma=NOISE[_noise_key(noise)], n_runs=runs)
    zf = thermocouples.random_failure(z, rng, "fixed")
    healthy = np.setdiff1d(np.arange(10), [3, 9])
    out: dict[str, float] = {}
    for key, arr in (("failure", zf), ("clean", z)):
        m = rd.fuse_epochs(arr[:, 49:80].reshape(-1, 10), "optimal_fusion_set").members
        out[key] = float(1.0 - m[:, healthy].mean())
    out["epochs"] = float(runs * 31)
    return out


@own_underflow  # underflow to 0 by design (a kernel, a density or normalised weights: fuzz 33b D6)
def support_bound_check(seed: int, n: int = 100_000, alpha: float = 0.25) -> dict[str, int]:
    """Check on random triples that support weighting cannot fall below the mean when the low reading is least supported.

    For three readings with gaps g1 (low to middle) >= g2 (middle to high) the low reading has the smallest
    support of :func:`fusion.readings.fusion_set.support_degree`, and the fused value is then at least the mean (the
    structural reason observations 3 and 4 of source Table 3 are out of reach). Readings are drawn uniform on
    [890, 910] °C.

    Parameters
    ----------
    seed : int
    n : int
        Number of random triples.
    alpha : float
        Support sharpness (°C⁻²).

    Returns
    -------
    dict
        ``"triples"``: triples drawn; ``"low_least"``: triples whose low reading is the least supported;
        ``"below"``: of those, triples whose fused value lies below the mean by more than 1e-9 °C.
    """
    seed = check_seed(seed)
    n = count(n, "n")  # a size: at most 10**7 triples (an (n, 3, 3) array of supports)
    alpha = scalar(alpha, "alpha", lo=0.0, lo_open=True)
    x = np.random.default_rng(seed).uniform(890.0, 910.0, (int(n), 3))
    fused = rd.fuse_epochs(x, "support_degree", alpha=float(alpha)).values
    sup = np.exp(-float(alpha) * (x[:, :, None] - x[:, None, :]) ** 2).sum(axis=2)
    low = np.argmin(x, axis=1)
    least = np.take_along_axis(sup, low[:, None], axis=1)[:, 0] <= sup.min(axis=1)
    below = fused < x.mean(axis=1) - 1e-9
    return {"triples": int(n), "low_least": int(least.sum()), "below": int((least & below).sum())}
