r"""How chapter 03 scores a claim about every sensor: the four sensors' paired comparisons as one
:class:`fusion.book.ledger.Conjunction` (:func:`sensor_conjunction`), and a cell of a study (:func:`cell`).
"""

from __future__ import annotations

from collections.abc import Callable, Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np

from fusion._results import ResultSpec, dict_of, instance, integer, trusted, validated_post_init
from fusion._frozen import constant
from fusion.book._few_runs import runs_named
from fusion.book.ledger import Comparison, Conjunction
from fusion.book.ledger.evidence import _MEMBER, _MEMBER_RUN
from fusion.book.rulebook import _runs_won
from fusion.book.style import METHOD_SHORT_LABELS
from fusion.scenarios.wavelet_sensors import Signal, SignalStudy, VarianceStudy
from fusion._counts import seed as check_seed, sequence
from fusion._docstrings import with_sections
from fusion._limits import work
from fusion._validation import as_array, instance_of, template, text
from fusion._shown import shown

__all__ = ["PRIMARY", "SIGNAL_TEXT", "sensor_conjunction", "status_text", "sign_conjunction", "Cell", "cell"]


#: The primary reading of every record: (signal, threshold rule, normaliser), with db4, 4 levels,
#: the universal threshold and the batch residual variance of the weights.
PRIMARY: tuple[Signal, str, str] = (Signal.TWO_TONES, "hard", "max")


#: Short descriptions of the signals of :data:`fusion.scenarios.wavelet_sensors.SIGNALS` (for the ledger).
SIGNAL_TEXT: dict[Signal, str] = constant({Signal.TWO_TONES: "2 + sin(2πn/256) + 0.5 sin(2πn/64)", Signal.SLOW: "2 + sin(2πn/256)",
                                  Signal.CONSTANT: "a steady measurand, 2",
                                  Signal.HEAVISINE: "piecewise smooth, Donoho-Johnstone"})


def _paired_metrics(a: object, b: object, a_name: object, b_name: object) -> tuple[np.ndarray, np.ndarray]:
    """``a`` and ``b`` as finite 2-D arrays of one shape (runs, sensors), and their names as strings, refused by name."""
    a, b = as_array(a, "a", ndim=2), as_array(b, "b", ndim=2)
    if a.shape != b.shape:
        raise ValueError(f"a and b must have the same shape (runs, sensors), got {a.shape} and {b.shape}")
    if a.shape[1] < 2:  # a claim about every sensor: a Conjunction holds at least two members (fuzz 18, F15)
        raise ValueError(f"a and b must hold at least two sensors (columns), got {a.shape[1]}")
    text(a_name, "a_name"), text(b_name, "b_name")
    return a, b


#: The Returns and Raises sections of :func:`sensor_conjunction` and :func:`sign_conjunction`, written once
#: (``{metric}`` filled with what the first says of its ``metric``, nothing for the second).
_PER_SENSOR_RETURNS = """\
fusion.book.ledger.Conjunction
    The parts ``("sensor j", Comparison)``, j = 1, 2, ..., one per column of ``a`` and ``b``, in order."""
_PER_SENSOR_RAISES = """\
TypeError
    ``a`` or ``b`` is not numeric, ``a_name`` or ``b_name``{metric} not a string, or ``seed`` not an integer.
ValueError
    ``a`` or ``b`` is not a non-empty 2-D array of finite values, their shapes differ, or they hold fewer than
    two sensors (columns) or fewer runs (rows) than rule R4's 100{metric_value}; or more sensors than the work
    budget of a :class:`fusion.book.ledger.Conjunction` (``fusion._limits.MAX_WORK``: 100,000 units a sensor and 300
    a run of it, about 7,700 sensors of 100 runs), counted before any sensor is compared."""


def _per_sensor(a: object, b: object, a_name: object, b_name: object, seed: int,
                part: Callable[[int, np.ndarray, np.ndarray, int], Comparison]) -> Conjunction:
    """``a``, ``b`` and the names checked (``seed`` is checked by the caller, before them), then
    ``part(j, a[:, j - 1], b[:, j - 1], seed)`` for each sensor j = 1, 2, ... joined as the Conjunction of
    ``"sensor j"`` parts."""
    a, b = _paired_metrics(a, b, a_name, b_name)
    # the Conjunction's own budget, a member per sensor at its runs, counted before any sensor's Comparison is built
    # (fuzz 68b C5: 100,000 sensors of 100 runs built a Comparison each, 0.16 ms apiece, and were refused by the
    # Conjunction after 17 CPU-s); the same units as ``Conjunction`` (its ``_MEMBER`` and ``_MEMBER_RUN``, measured there)
    work((a.shape[1],), "a and b (sensors x runs)", weight=_MEMBER + _MEMBER_RUN * a.shape[0])
    with runs_named("a and b", "a row of a and b per run"):   # no argument reason here (fuzz 29b B6)
        return Conjunction(tuple((f"sensor {j + 1}", part(j + 1, a[:, j], b[:, j], seed))
                                 for j in range(a.shape[1])))


@with_sections(returns=_PER_SENSOR_RETURNS, raises=_PER_SENSOR_RAISES.format(
    metric=" (or ``metric``)", metric_value="; or ``metric`` holds a field other than ``{j}``, a width above 99 "
    "(``{j:>1000}``) or unbalanced braces (the template rule of ``fusion._validation.template``)"))
def sensor_conjunction(a: np.ndarray, b: np.ndarray, a_name: str, b_name: str, metric: str, seed: int,
                       claim: str = "less") -> Conjunction:
    """One paired comparison per sensor (columns of ``a`` and ``b``), joined: the claim is about every sensor.

    Parameters
    ----------
    a, b : ndarray, shape (runs, sensors)
        Per-run metric of A and of B.
    a_name, b_name : str
        What A and B are (the sensor is appended).
    metric : str
        What is compared: a :meth:`str.format` template whose only field is ``{j}``, replaced by the sensor's
        number (``"RMSE, sensor {j}"``; a text without a field is the same for every sensor).
    seed : int
        Seed of the runs.
    claim : {"less", "greater"}
        What the source claims of A against B.
    """
    sd = check_seed(seed)
    metric = template(metric, "metric", j=1)  # before any part is formatted (fuzz 21b, W)
    a_name, b_name = text(a_name, "a_name"), text(b_name, "b_name")  # the plain text in the labels (rule 19)
    return _per_sensor(a, b, a_name, b_name, sd,
                       lambda j, aj, bj, sd: Comparison(aj, bj, f"{a_name} (sensor {j})", f"{b_name} (sensor {j})",
                                                        claim, metric.format(j=j), seed=sd))


def status_text(c: Conjunction) -> str:
    """``"reproduced"``, or the status with the sensors that decide it (``"not distinguishable: sensor 4"``).

    Parameters
    ----------
    c : fusion.book.ledger.Conjunction

    Returns
    -------
    str
        ``"reproduced"``, else the conjunction's status and the numbers of the sensors that have it
        (``"contradicted: sensors 2, 4"``).

    Raises
    ------
    TypeError
        ``c`` not a Conjunction.
    """
    instance_of(c, Conjunction, "c")
    st = c.status()
    if st == "reproduced":
        return st
    bad = [lab.replace("sensor ", "") for lab, ev in c.parts if ev.status() == st]
    return f"{st}: sensor{'s' if len(bad) > 1 else ''} {', '.join(bad)}"


@with_sections(returns=_PER_SENSOR_RETURNS, raises=_PER_SENSOR_RAISES.format(metric="", metric_value=""))
def sign_conjunction(a: np.ndarray, b: np.ndarray, a_name: str, b_name: str, seed: int) -> Conjunction:
    """Per sensor: is A better than B in more than half of the runs (the median paired difference below 0)?

    A sign test written as a paired comparison: the indicator of ``A < B`` in each run against one
    half, so that the ledger's interval is the normal (Wald) interval of the fraction of runs won (a tie, a
    difference within round-off of zero, is never a win: the rulebook's share of runs won, R3). It
    reads the claim by the *typical* run, where :func:`sensor_conjunction` reads it by the mean, which a
    few runs with a large loss can carry.

    Parameters
    ----------
    a, b : ndarray, shape (runs, sensors)
        Per-run metric of A and of B.
    a_name, b_name : str
        What A and B are.
    seed : int
        Seed of the runs.
    """
    a_name, b_name = text(a_name, "a_name"), text(b_name, "b_name")  # the plain text in the labels (rule 19)
    return _per_sensor(a, b, a_name, b_name, check_seed(seed),
                       lambda j, aj, bj, sd: Comparison(_runs_won(aj, bj, "less").astype(float),
                                                        np.full(aj.shape[0], 0.5),
                                                        f"fraction of runs in which {a_name} beats {b_name} "
                                                        f"(sensor {j})", "one half", "greater",
                                                        "fraction of runs won (sign test)", seed=sd))


@dataclass(frozen=True)
class Cell:
    """One case of a signal study, with the run count and seed of the study it comes from (:func:`cell`).

    Attributes
    ----------
    case : mapping of str to object
        The case of :attr:`fusion.scenarios.wavelet_sensors.SignalStudy.cases`: each estimate's metrics by its key
        (``"raw"``, ``"denoised"``, ``"reconstructed"``, ...), ``"gain_err"``, ``"weights"`` and ``"example"``.
    runs, seed : int
        Runs and seed of the study the case comes from.
    """

    case: Mapping[str, Any]
    runs: int
    seed: int

    __result_spec__ = ResultSpec({"case": dict_of(instance(Mapping, np.ndarray),
                                                  required=("raw", "denoised", "reconstructed", "gain_err", "weights")),
                                  "runs": integer(2), "seed": integer(0)})
    __post_init__ = validated_post_init



def _holds(cases: Mapping[Any, Any], key: object) -> bool:
    """Whether ``key`` is a case of ``cases`` (False for an unhashable key)."""
    try:
        return key in cases
    except TypeError:
        return False


def _same_setup(e26: SignalStudy, gains: np.ndarray, sigma: np.ndarray, length: int, other: str) -> None:
    """Refuse E2.6 read beside the numbers of a study of another setup (fuzz 26d B; fuzz 32b D3: the signal table took
    its primary cell from a study of equal gains): ValueError naming ``e26`` and ``other`` unless both have the same
    gains, sigma and signal length. The one rule of every reader of ``e26`` (:func:`cell`, ``mechanism``'s)."""
    if not (np.array_equal(e26.gains, gains) and np.array_equal(e26.sigma, sigma) and e26.length == length):
        raise ValueError(f"e26 is a study of another setup than {other}: gains {e26.gains.tolist()}, sigma "
                         f"{e26.sigma.tolist()}, length {e26.length}; {other} has gains {np.asarray(gains).tolist()}, "
                         f"sigma {np.asarray(sigma).tolist()}, length {length}")


def cell(sg: SignalStudy, e26: SignalStudy | None, key: tuple[Signal, str, str]) -> Cell:
    """The case ``key`` = (signal, rule, normaliser): from E2.6 (more runs) when it holds it, else from ``sg``.

    Parameters
    ----------
    sg : SignalStudy
        :func:`fusion.scenarios.wavelet_sensors.signal_study` over the signals and rules.
    e26 : SignalStudy or None
        The same study for the primary signal and rule only, with more runs (E2.6): the same setup as ``sg`` (gains,
        sigma, signal length), else a ValueError naming both.
    key : (Signal, str, str)

    Returns
    -------
    Cell
        The case, with the runs and seed of the study it comes from.
    """
    instance_of(sg, SignalStudy, "sg")
    if e26 is not None:
        instance_of(e26, SignalStudy, "e26")
        _same_setup(e26, sg.gains, sg.sigma, sg.length, "sg")
    key = tuple(sequence(key, "key", 3))  # a tuple or a list (fuzz 24e F2-F3: the package's sequence rule)
    src = e26 if e26 is not None and _holds(e26.cases, key) else sg
    if not _holds(src.cases, key):
        raise ValueError(f"key must be a (signal, rule, normaliser) case of sg or e26, got {shown(key, 80)}")
    # the study's case, already frozen and read-only: built without re-checking it (a table reads many cells)
    return trusted(Cell, case=src.cases[key], runs=int(src.runs), seed=int(src.seed))


def _e26_case(e: SignalStudy, nm: str, name: str = "e") -> Mapping[str, Any]:
    """The primary signal and rule's case of E2.6 with normaliser ``nm`` (as :attr:`Cell.case`); a study of the right
    type that lacks it (another study's cases, fuzz 18's D20) is a ValueError naming the argument ``name``."""
    key = (e.signals[0], e.modes[0], nm) if e.signals and e.modes else None
    if key is None or not _holds(e.cases, key):
        raise ValueError(f"{name} lacks the normaliser {shown(nm)} of its first signal and rule (it holds the normalisers "
                         f"{list(e.normalisers)}): it is not the study this function reads")
    return e.cases[key]


_METRIC = {"mse": "MSE against g{j}S", "evar": "ensemble error variance (bias excluded)",
           "tvar": "temporal variance of the data (constant measurand)"}


def _q(sg: SignalStudy, key: tuple[Signal, str, str], a: str, b: str, metric: str,
       e26: SignalStudy | None = None) -> Conjunction:
    c = cell(sg, e26, key)
    return sensor_conjunction(c.case[a][metric], c.case[b][metric], METHOD_SHORT_LABELS[a], METHOD_SHORT_LABELS[b],
                              _metric_label(sg, metric), c.seed)


def _metric_label(study_: SignalStudy | VarianceStudy, metric: str) -> str:
    """The metric's label; the MSE is against S on the lecture's model (equal gains), against gⱼS otherwise."""
    if metric == "mse" and np.allclose(np.asarray(study_.gains, dtype=float), 1.0):
        return "MSE against S"
    return _METRIC[metric]
