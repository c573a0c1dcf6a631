r"""Lecture §2.2 (E2.2): variance learning, its limit, learned and corrected weights."""

from __future__ import annotations

from dataclasses import dataclass
from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np

from fusion._results import ResultSpec, array, dict_of, instance, integer, number, text, tuple_of, validated_post_init
from fusion._shown import shown
from fusion._validation import read_once
from fusion._validation import as_array, derived_inputs
from fusion._validation import count, scalar, sequence
from fusion._validation import allocation
from fusion._counts import input_allocation
from fusion._validation import LOOP_STEP, MAX_MAGNITUDE, distinct, work
from fusion.readings import weighting as wt
from fusion.scenarios._lecture_checks import _ints, _seed, _sigmas

__all__ = [
    "LearningRow",
    "LearnedLimitCheck",
    "LearningStudy",
    "learning_study",
    "learned_limit_check",
    "MAX_LOG_RANGE",
]


# --------------------------------------------------------------------------- E2.2
@dataclass(frozen=True)
class LearningRow:
    """One variance setting of E2.2 (a row of :attr:`LearningStudy.rows`).

    Attributes
    ----------
    R : str
        The true variances, as written in the table (``"(1, 4, 9)"``).
    min_r : float
        The best sensor's variance, min Rᵢ.
    optimal : float
        The fused variance with the optimal weights.
    learned_limit : float
        The exact fused variance with the learned weights' limit.
    learned_mc : float
        The learned fusion's Monte-Carlo MSE over the last epochs.
    mean : float
        The arithmetic mean's variance.
    max_rel_limit_dev : float
        Largest relative deviation of the mean learned variances from their limit at the last epoch.
    corrected_mc : float
        The corrected learning's Monte-Carlo MSE (NaN for n = 2).
    """

    R: str
    min_r: float
    optimal: float
    learned_limit: float
    learned_mc: float
    mean: float
    max_rel_limit_dev: float
    corrected_mc: float

    __result_spec__ = ResultSpec(
        {"R": text(), "min_r": number(positive=True), "optimal": number(positive=True),
         "learned_limit": number(positive=True), "learned_mc": number(), "mean": number(positive=True),
         "max_rel_limit_dev": number(), "corrected_mc": number(nan=True)})  # NaN for n = 2 (no corrected learning)
    __post_init__ = validated_post_init


def _learning_relation(values: Mapping[str, Any], cls: str) -> None:
    """A :class:`LearningStudy`: one row, one ``bias`` entry (keyed by the row's ``R``) and one ``learned`` entry per
    setting; ``learned[n]`` the n true variances (> 0) and their mean learned estimates (>= 0), shape (epochs, n),
    the same epochs for every n, at least ``last``."""
    rows, learned = values["rows"], values["learned"]
    if set(values["bias"]) != {row.R for row in rows} or len(learned) != len(rows):
        raise ValueError(f"{cls}.bias and {cls}.learned must hold one entry per row of {cls}.rows ({len(rows)}), "
                         f"got {len(values['bias'])} and {len(learned)}")
    epochs = None
    for n, (R, mean) in learned.items():
        where = f"{cls}.learned[{shown(n)}]"
        R = as_array(R, f"{where}[0]", ndim=1, shape=(n,))
        mean = as_array(mean, f"{where}[1]", ndim=2, shape=(epochs, n), nonnegative=True)
        if np.any(R <= 0):
            raise ValueError(f"{where}[0] must hold positive variances, got {shown(R)}")
        epochs = mean.shape[0]
    if epochs is not None and values["last"] > epochs:
        raise ValueError(f"{cls}.last must be at most the {epochs} epochs of {cls}.learned, got {values['last']}")


@dataclass(frozen=True)
class LearningStudy:
    """Experiment E2.2: variance learning of sec. 2.2 (:func:`learning_study`).

    Attributes
    ----------
    rows : tuple of LearningRow
        One per setting.
    learned : mapping
        n → (R, mean learned variances against m, shape (epochs, n)).
    bias : mapping
        R → per-run mean error of the learned fusion over the last ``last`` epochs, shape (runs,).
    x : float
        The constant measured value.
    last : int
        Epochs averaged for ``bias``.
    n2_maxdev : float
        Largest deviation of the two-sensor learned weights from 1/2.
    """

    rows: tuple[LearningRow, ...]
    learned: Mapping[int, tuple[np.ndarray, np.ndarray]]
    bias: Mapping[str, np.ndarray]
    x: float
    last: int
    n2_maxdev: float

    __result_spec__ = ResultSpec(
        {"rows": tuple_of(instance(LearningRow)),
         "learned": dict_of(tuple_of(instance(np.ndarray), instance(np.ndarray)), key=int),  # n differs per key
         "bias": dict_of(array("runs")), "x": number(nonnegative=False), "last": integer(1), "n2_maxdev": number()},
        relations=(lambda v, cls: _learning_relation(v, cls),))
    __post_init__ = validated_post_init


#: Units of work of :func:`learning_study`: a reading (run x epoch x sensor of a set) 15 units, a set 40 ``LOOP_STEP``
#: (fuzz 42a C5; 10 ``LOOP_STEP`` a set over runs x epochs were counted, whatever its sensors: 1,000 sensors of 2 runs x
#: 2,000 epochs counted 1e5 units and ran 0.33 CPU-s). Measured (``time.process_time``, ``OPENBLAS_NUM_THREADS=1``,
#: the least of two calls, machine shared): 14.7 units a reading for the default four sets (200 x 2,000, 0.82 CPU-s),
#: 12.4 at 20 sensors, 11.0 at 200 (20 runs), 8.2 at 1,000 (2 runs); 500 sets of 2 to 501 sensors of 1 run x 2 epochs
#: 0.43 ms a set (0.35 ms beside their readings).
_LEARNING_READING, _LEARNING_SET = 15, 40 * LOOP_STEP


def learning_study(
    r_sets: Sequence[Sequence[float]] = ((1.0, 4.0), (1.0, 4.0, 9.0), (1.0, 2.0, 4.0, 8.0), (0.25, 1.0, 4.0, 16.0, 64.0)),
    epochs: int = 2000,
    runs: int = 200,
    x: float = 50.0,
    seed: int = 2202,
    seed_two: int = 2203,
    last: int = 200,
) -> LearningStudy:
    r"""Experiment E2.2: the variance-learning recursion of sec. 2.2.

    Parameters
    ----------
    r_sets : sequence of variance tuples
        True noise variances :math:`R_i` of each setting (one generator draws all settings in turn), no two
        settings of the same size (the learned variances are keyed by size).
    epochs, runs : int
    x : float
        True value.
    seed, seed_two : int
        Seeds of the settings and of the two-sensor check (50 runs x 300 epochs, R = (1, 4)).
    last : int
        Monte-Carlo MSEs are over the last ``last`` epochs.

    Returns
    -------
    LearningStudy
        The table's rows per set of variances, the learned variances per set size and each run's mean error over the
        last epochs.

    Raises
    ------
    TypeError
        ``r_sets`` or one of its sets not a sequence of numbers, named.
    ValueError
        A bad argument, named; a set of fewer than 2 or non-positive variances, two sets of one size; the sets' work
        (15 units a reading, runs x epochs x its variances, and 40,000 a set, measured) beyond the work budget, or
        the largest set's readings beyond the memory or input budget, naming r_sets, runs and epochs, before any draw.
    """
    r_sets = read_once(r_sets, "r_sets")  # a Sequence class read once (fuzz 31a C4)
    if isinstance(r_sets, (str, bytes)):
        raise TypeError("r_sets must be a sequence of variance tuples, got a string")
    epochs = count(epochs, "epochs")
    runs = count(runs, "runs")
    allocation((runs, epochs), "runs, epochs and r_sets")  # rule 9 first: one sensor's readings already too many
    # rule 17, each set counted as it is read (fuzz 42a C5): its entry converted once (never its len(), which an
    # array-like with only __array__ lacks, nor a second conversion, which may give more variances than the first) and
    # that array is what is counted and run; the sets' work summed, refused at the first set beyond the budget
    sets, units = [], 0
    for Rt in sequence(r_sets, "r_sets"):
        R = _sigmas(read_once(Rt, "r_sets"), "r_sets")  # positive variances, as _sigmas' positive SDs
        units += _LEARNING_SET + _LEARNING_READING * runs * epochs * R.size
        work((units,), "r_sets, runs and epochs")
        sets.append(R)
    n_max = max((R.size for R in sets), default=1)
    allocation((runs, epochs, n_max), "runs, epochs and r_sets")
    input_allocation((runs, epochs, n_max), "runs, epochs and r_sets")  # the readings Y are its fusions' input
    sizes = [R.size for R in sets]
    if len(set(sizes)) != len(sizes):  # the learned variances are keyed by the set's size
        raise ValueError(f"r_sets must hold sets of different sizes (the learned variances are keyed by size), "
                         f"got sizes {sizes}")
    x = scalar(x, "x")
    seed = _seed(seed)
    seed_two = _seed(seed_two, "seed_two")
    last = count(last, "last")
    if last > epochs:
        raise ValueError(f"last must be <= epochs = {epochs}, got {last}")
    rng = np.random.default_rng(seed)
    rows, learned, bias = [], {}, {}
    for R in sets:
        n = R.size
        Y = x + rng.normal(size=(runs, epochs, n)) * np.sqrt(R)
        Rh = wt.learned_variances(Y)
        learned[n] = (R, Rh.mean(axis=0))
        limit = wt.learned_variance_limit(R)
        row = LearningRow(
            R="(" + ", ".join(f"{float(r):g}" for r in R) + ")", min_r=float(R.min()),
            optimal=float(wt.minimum_variance(R)), learned_limit=float(np.sum(wt.optimal_weights(limit) ** 2 * R)),
            learned_mc=float(np.mean((wt.ls_learning(Y).values[:, -last:] - x) ** 2)), mean=float(R.sum() / n**2),
            max_rel_limit_dev=float(np.max(np.abs(Rh[:, -1].mean(axis=0) - limit) / limit)),
            corrected_mc=(float(np.mean((wt.ls_learning(Y, corrected=True).values[:, -last:] - x) ** 2))
                          if n >= 3 else float("nan")))
        rows.append(row)
        bias[row.R] = (wt.ls_learning(Y).values[:, -last:] - x).mean(axis=1)
    Y2 = x + np.random.default_rng(seed_two).normal(size=(50, 300, 2)) * np.sqrt([1.0, 4.0])
    return LearningStudy(rows=rows, learned=learned, bias=bias, x=x, last=last,
                         n2_maxdev=float(np.max(np.abs(wt.ls_learning(Y2).weights - 0.5))))


@dataclass(frozen=True)
class LearnedLimitCheck:
    """Random check of the learned weights' limit against the mean and the best sensor (:func:`learned_limit_check`).

    Attributes
    ----------
    sets : int
        Variance sets drawn in total.
    above_mean : int
        Sets where the learned fusion's variance exceeds the mean's by more than 10⁻¹² relative.
    above_best : int
        Sets where it exceeds the best sensor's by more than ``margin``.
    above_best_any : int
        Sets where it exceeds the best sensor's by any amount.
    max_ratio_mean : float
        Largest learned/mean variance ratio.
    margin : float
        The practical margin (a share of the best sensor's variance).
    ns : tuple of int
        Numbers of sensors.
    draws, seed : int
        Variance sets per n, seed.
    """

    sets: int
    above_mean: int
    above_best: int
    above_best_any: int
    max_ratio_mean: float
    margin: float
    ns: tuple[int, ...]
    draws: int
    seed: int

    __result_spec__ = ResultSpec(
        {"sets": integer(1), "above_mean": integer(0), "above_best": integer(0), "above_best_any": integer(0),
         "max_ratio_mean": number(positive=True), "margin": number(), "ns": tuple_of(integer(2)),
         "draws": integer(1), "seed": integer(0)},
        relations=(lambda v, cls: _limit_check_relation(v, cls),))
    __post_init__ = validated_post_init


def _limit_check_relation(values: Mapping[str, Any], cls: str) -> None:
    """A :class:`LearnedLimitCheck`: ``draws`` sets per n, counts of them at most ``sets``, beyond the margin at most
    beyond any amount."""
    if values["sets"] != values["draws"] * len(values["ns"]):
        raise ValueError(f"{cls}.sets must be {cls}.draws x the {len(values['ns'])} {cls}.ns = "
                         f"{values['draws'] * len(values['ns'])}, got {values['sets']}")
    for name in ("above_mean", "above_best", "above_best_any"):
        if values[name] > values["sets"]:
            raise ValueError(f"{cls}.{name} must be at most {cls}.sets = {values['sets']}, got {values[name]}")
    if values["above_best"] > values["above_best_any"]:
        raise ValueError(f"{cls}.above_best must be at most {cls}.above_best_any = {values['above_best_any']} "
                         f"(beyond the margin is beyond any amount), got {values['above_best']}")


#: Largest half-width a of :func:`learned_limit_check`'s log-variances, ``ln(MAX_MAGNITUDE)`` (about 345.4): every variance
#: :math:`e^{u}`, :math:`|u| \le a`, stays within the package's range [1e-150, 1e150] (fuzz 26d W3: a larger a was
#: refused as a "derived quantity" naming every argument).
MAX_LOG_RANGE = float(np.log(MAX_MAGNITUDE))


#: The numbers of sensors of :func:`learned_limit_check` by default (the chapter's, and every half-width of its spread
#: check, ``fusion.book.chapters.lecture_weighting.learning.spread_check``).
_CHECK_NS = (3, 4, 5, 6, 7, 8)


def _limit_check_units(ns: Sequence[int], draws: int) -> int:
    """The units of work (rule 17) of one :func:`learned_limit_check` of ``ns`` sensors (checked) and ``draws`` sets: a
    loop step per n and 8 units a variance (draws x sum(ns)): 3.7e6 draws of the default ``ns``, 9.8e8 units, ran 10.4
    CPU-s (fuzz 42b C8). The one count of it and of a caller that runs it in a loop."""
    return len(ns) * LOOP_STEP + 8 * draws * int(sum(ns))


@derived_inputs()
def learned_limit_check(ns: Sequence[int] = _CHECK_NS, draws: int = 20000, seed: int = 2204,
                        log_range: float = 4.0, margin: float = 0.05) -> LearnedLimitCheck:
    r"""Random check of the learned weights' limit of sec. 2.2 against the mean and the best sensor.

    For every n of ``ns``, ``draws`` variance sets :math:`R_i = e^{u_i}`, :math:`u_i \sim U(-a, a)`
    (a = ``log_range``); the fused variance with the learned weights' limit
    (:func:`fusion.readings.weighting.learned_fused_variance`) against the arithmetic mean's
    :math:`\sum R_i/n^2` and the best sensor's :math:`\min R_i`.

    Parameters
    ----------
    ns : sequence of int
        Numbers of sensors (each >= 2, no two equal).
    draws : int
        Variance sets per n (draws x sum(ns) within the work budget, ``fusion._validation.MAX_WORK``).
    seed : int
    log_range : float
        Half-width a of the uniform log-variances (> 0, at most :data:`MAX_LOG_RANGE`, about 345: the variances stay
        within the package's numeric range).
    margin : float
        Practical margin, a share of the best sensor's variance (>= 0; rule R9: "no worse than the best sensor"
        fails only beyond it).

    Returns
    -------
    LearnedLimitCheck
        Of ``sets`` random sets: how many fused variances at the limit exceed the mean's, and the best sensor's, and the
        largest ratio to the mean's.
    """
    n_arr = _ints(ns, "ns", minimum=2)
    draws = count(draws, "draws")
    allocation((draws, int(n_arr.max())), "ns and draws")
    input_allocation((draws, int(n_arr.max())), "ns and draws")  # the variance sets are the weights' input
    work((_limit_check_units(n_arr.tolist(), draws),), "ns and draws")  # rule 17: draws x sum(ns)
    distinct(n_arr.tolist(), "ns")  # one rule for sizes: a repeated n would draw its sets twice (after the budget)
    seed = _seed(seed)
    a = scalar(log_range, "log_range", lo=0.0, lo_open=True, hi=MAX_LOG_RANGE)
    m = scalar(margin, "margin", lo=0.0)
    rng = np.random.default_rng(seed)
    above_mean = above_best = above_any = 0
    worst = 0.0
    for n in n_arr.astype(int):
        R = np.exp(rng.uniform(-a, a, size=(draws, n)))
        v = wt.learned_fused_variance(R)
        mean = R.sum(axis=1) / n**2
        above_mean += int(np.sum(v > mean * (1 + 1e-12)))
        above_best += int(np.sum(v > R.min(axis=1) * (1 + m)))
        above_any += int(np.sum(v > R.min(axis=1)))
        worst = max(worst, float(np.max(v / mean)))
    return LearnedLimitCheck(sets=int(draws * n_arr.size), above_mean=above_mean, above_best=above_best,
                             above_best_any=above_any, max_ratio_mean=worst, margin=m,
                             ns=tuple(int(n) for n in n_arr), draws=draws, seed=seed)
