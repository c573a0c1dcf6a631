"""Chapter 07 (Shi, Suo & Ma 2023): the robustness studies of the time-registration chapter's appendix.

The improved method against two-point interpolation under the book's stress tests: the robustness table of the
ledger's readings, an unmodelled delay (table and break-even delay) and the readings themselves. Re-exported by
:mod:`fusion.book.chapters.time_registration`.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from typing import TYPE_CHECKING

import numpy as np
import pandas as pd
from numpy.typing import ArrayLike

from fusion._results import ResultSpec, dict_of, instance, text, validated_post_init
from fusion._shown import shown
from fusion.book.tables import integral_index
from fusion.scenarios import time_registration as sc
from fusion.scenarios.time_registration import RegMethod
from fusion.book._t_interval import mean_interval

if TYPE_CHECKING:  # the ledger's study type (its module imports the chapter module, which imports this one)
    from fusion.book.chapters.time_registration_ledger.studies import RegistrationStudy

__all__ = ["robustness_table", "delay_table", "delay_break_even", "RobustnessReading", "robustness_readings"]


def _options_relation(values: Mapping[str, object], cls: str) -> None:
    """The options are keyword arguments of :func:`fusion.scenarios.time_registration.monte_carlo`."""
    import inspect

    allowed = [p.name for p in inspect.signature(sc.monte_carlo).parameters.values() if p.kind is p.KEYWORD_ONLY]
    unknown = [k for k in values["options"] if k not in allowed]
    if unknown:
        raise ValueError(f"{cls}.options must be keyword arguments of monte_carlo ({', '.join(allowed)}), "
                         f"got {shown(unknown)}")


@dataclass(frozen=True)
class RobustnessReading:
    """One open choice or stress test of the §3-4 comparison (:func:`robustness_readings`).

    Attributes
    ----------
    key : str
        The reading's key in ``book/claims/shi2023time.yaml`` (record ``shi-improved``).
    choice : str
        The table's label of the choice.
    reading : str
        The table's label of the reading.
    options : dict
        Keyword arguments of :func:`fusion.scenarios.time_registration.monte_carlo` that make the reading.
    """

    key: str
    choice: str
    reading: str
    options: Mapping[str, object]

    __result_spec__ = ResultSpec({"key": text(), "choice": text(), "reading": text(),
                                  "options": dict_of(instance(Mapping, float, int, np.ndarray))},
                                 relations=(lambda v, cls: _options_relation(v, cls),))
    __post_init__ = validated_post_init


TWO = RegMethod.TWO_POINT
IMPROVED = RegMethod.IMPROVED


def _paired(a: np.ndarray, b: np.ndarray) -> tuple[float, float, float]:
    low, high = mean_interval(a - b, 0.95)   # scipy's ttest_rel is ttest_1samp(a - b); no warning (fuzz 37b C3)
    return float(np.mean(a - b)), low, high


#: Column headers of the paired intervals, shared by this module's tables and the chapter module's benchmark and
#: offline tables (issue 36: named once, read by name).
CI_LOW = "95 % CI low"
CI_HIGH = "95 % CI high"
IMPROVED_IS = "improved is"


def robustness_table(st: RegistrationStudy) -> pd.DataFrame:
    """The headline (improved minus two-point, paired over the same runs) under each reading of :func:`robustness_readings`.

    Parameters
    ----------
    st : RegistrationStudy
        The chapter's :func:`~fusion.book.chapters.time_registration_ledger.study` (its ``robust`` runs, ``sigma`` and ``t2``).

    Returns
    -------
    DataFrame
        Index (choice, reading); runs, mean paired difference (m²), its 95 % interval, verdict.
    """
    from fusion._validation import instance_of
    from fusion.book.chapters.time_registration_ledger.studies import RegistrationStudy

    instance_of(st, RegistrationStudy, "st")
    rows = {}
    for rd in robustness_readings(st.sigma, st.t2):
        m = st.robust[rd.key]
        d, lo, hi = _paired(m.per_run[IMPROVED], m.per_run[TWO])
        rows[(rd.choice, rd.reading)] = {"runs": m.runs, "improved minus two-point (m²)": d, CI_LOW: lo, CI_HIGH: hi,
                        IMPROVED_IS: "better" if hi < 0 else "worse" if lo > 0 else "not distinguishable"}
    out = pd.DataFrame(rows).T.infer_objects()
    out.index.names = ["choice", "reading"]
    num = ["improved minus two-point (m²)", CI_LOW, CI_HIGH]
    out[num] = out[num].astype(float).round(4) + 0.0
    return out


def _delay_row(d: float) -> float:
    """The row label of latency ``d`` (s) in :func:`delay_table`: milliseconds to 6 decimals."""
    return round(1e3 * d, 6)


def delay_table(delays: Sequence[float], sigmas: Sequence[float]) -> pd.DataFrame:
    """Exact E[MSE] of the improved method minus two-point interpolation under a latency of sensor 1.

    The sample stamped :math:`t_i` is taken at :math:`t_i - \\delta` (``delay``); neither method models it.

    Parameters
    ----------
    delays : sequence of float
        Latencies δ (s); negative: the sample is taken after its stamp. Each keeps sensor 1's true sample times in
        the 40 s flight, where the truth is the UAV's: from -1 s to 1 s (see
        :func:`fusion.scenarios.time_registration.expected`); a larger one (``1e9`` s gave -4.2e23 m²) is refused.
    sigmas : sequence of float
        Noise levels (m), also assumed by the filter.

    Returns
    -------
    DataFrame
        Index δ (ms); one column per σ, improved minus two-point (m², 4 decimals; negative: improved better).

    Raises
    ------
    TypeError
        ``delays`` or ``sigmas`` is not a sequence of numbers.
    ValueError
        ``delays`` or ``sigmas`` is empty or repeats an entry, or two entries print the same label (δ in ms to 6
        decimals, σ to 6 significant digits: the table is keyed by them, a repeat would merge into one row or
        column), a latency is not finite or outside the flight, a noise level is not a valid standard
        deviation, or the table is beyond the work budget (``fusion._limits.MAX_WORK``, chapter 07's rule
        ``_registration_work``: 592 cells, latencies x levels).
    """
    from fusion._validation import distinct_printed, general, scalar, sequence, std_scalar

    lo, hi = sc._delay_bounds(*sc.instants())  # the true sample times in the flight (-1 s to 1 s)
    read = {}   # the checked floats, read once: budgeted and looped over (fuzz 58a D1: the caller's objects were
    # iterated again, and a list subclass yielding 20,000 latencies the second time ran unbudgeted > 120 s)
    items = {name: sequence(values, name) for name, values in (("delays", delays), ("sigmas", sigmas))}
    for name, got in items.items():
        if not got:
            raise ValueError(f"{name} is empty")
    # rule 17 before any work (fuzz 28b D3): two exact MSEs per cell, the cells counted in closed form by the two
    # lengths before any entry is read (fuzz 60a C3: a list of len(delays) x len(sigmas) counts was built first,
    # 15.4 CPU-s at 20,000 x 20,000, a raw MemoryError at 100,000 x 100,000)
    sc._exact_work((IMPROVED, TWO), {sc.instants()[1].size: len(items["delays"]) * len(items["sigmas"])},
                   "delays and sigmas", period_change=False)
    for name, check, printed in (("delays", lambda v, n: scalar(v, n, lo, hi), _delay_row),
                                 ("sigmas", std_scalar, general)):
        read[name] = [float(check(v, f"{name}[{i}]")) for i, v in enumerate(items[name])]
        distinct_printed(read[name], name, printed, "labels a row or column")
    checked_delays, checked_sigmas = read["delays"], read["sigmas"]
    rows = {_delay_row(d): {f"σ_x = {s:g} m": sc.expected(IMPROVED, s, delay=d) - sc.expected(TWO, s, delay=d)
                            for s in checked_sigmas} for d in checked_delays}
    out = pd.DataFrame(rows).T
    out.index.name = "latency δ (ms)"
    return integral_index(out.round(4) + 0.0)


def delay_break_even(sigma: float, upper: float = 0.05) -> float:
    """Smallest positive latency (s) of sensor 1 at which two-point interpolation matches the improved method.

    Parameters
    ----------
    sigma : float
        Noise level (m), also assumed by the filter.
    upper : float
        Upper end of the search (s), at most 1 s; the difference must change sign on ``(0, upper]``.

    Returns
    -------
    float
        The latency, rounded to 0.1 ms.

    Raises
    ------
    TypeError
        ``sigma`` or ``upper`` is not a number.
    ValueError
        ``sigma`` is not a valid standard deviation; ``upper`` is not in ``(0, 1]`` s (sensor 1's first sample
        is stamped 1 s: a larger latency would put its true time before the flight starts at t = 0, and
        ``upper = 1e50`` returned itself); or there is no sign change on ``(0, upper]``.
    """
    from scipy.optimize import brentq

    from fusion._validation import scalar, std_scalar

    first = float(sc.instants()[0][0])  # sensor 1's first sample time: the latency that takes it at t = 0
    sigma, upper = std_scalar(sigma, "sigma"), scalar(upper, "upper", lo=0.0, hi=first, lo_open=True)

    def diff(d: float) -> float:
        return sc.expected(IMPROVED, sigma, delay=d) - sc.expected(TWO, sigma, delay=d)

    if diff(0.0) * diff(upper) > 0:
        raise ValueError(f"upper: no change of order on (0, {upper}] s at sigma = {sigma}")
    return round(float(brentq(diff, 0.0, upper, xtol=1e-6)), 4)


def robustness_readings(sigma: float, t2: ArrayLike) -> list[RobustnessReading]:
    """The open choices and stress tests of the §3-4 comparison, each a :class:`RobustnessReading` (key, choice,
    reading, keyword arguments of :func:`fusion.scenarios.time_registration.monte_carlo`); the key is the reading's
    key in ``book/claims/shi2023time.yaml`` (record ``shi-improved``), the labels are the table's.

    Parameters
    ----------
    sigma : float
        Measurement noise SD (m) of the study (the "filter assumes 2σ" reading doubles it).
    t2 : array_like
        Registration instants (s) of the primary scenario (the start-up reading scores from the third).

    Returns
    -------
    list of RobustnessReading
        Sixteen readings: initial covariance, Kalman tuning, driving noise and filter period,
        initialisation, the filter's noise level, start-up, period ratio; latency and manoeuvre (stress).

    References
    ----------
    * Blair, W. D., Rice, T. R., Alouani, A. T., & Xia, P. (1991). Asynchronous data fusion for target tracking
      with a multi-task radar and optical sensor. Proc. SPIE 1482.
    """
    from fusion._validation import as_times, std_scalar

    sigma, T2 = std_scalar(sigma, "sigma"), as_times(t2, "t2")   # the instants read once, used (fuzz 61a C4's class)
    SIGMA = sigma
    T2_6 = sc.instants(6.0)[1]                   # integer ratio 3: instants coincide with sensor-1 samples
    return [RobustnessReading(*r) for r in (  # (key, choice, reading, options)
        ("p0-small", "initial covariance", "P0 = diag(σ², 1, 1)", dict(kf={"p0": (1.0, 1.0)})),
        ("p0-large", "initial covariance", "P0 = diag(σ², 10^4, 10^4)", dict(kf={"p0": (1e4, 1e4)})),
        ("q-small", "Kalman tuning", "q_v = 10^-4, q_a = 10^-5 per step", dict(q_v=1e-4, q_a=1e-5)),
        ("q-large", "Kalman tuning", "q_v = 1, q_a = 0.1 per step", dict(q_v=1.0, q_a=0.1)),
        ("per-step-period-changed", "filter period (out of scope)", "per-step Q, period changed at the instants",
         dict(kf={"period_change": True})),
        ("wnj-period-changed", "filter period (out of scope)", "white-noise-jerk Q(T), period changed",
         dict(kf={"q_model": "white-noise jerk", "period_change": True})),
        ("z1-once", "initialisation", "first measurement used once", dict(kf={"init": "once"})),
        ("filter-2sigma", "filter's noise level", "filter assumes 2σ", dict(sigma_filter=2 * SIGMA)),
        ("start-up", "instants scored", "from the third instant (13 s) on", dict(t_dst=T2[2:])),
        ("integer-ratio", "period ratio (out of scope)", "sensor 2 every 6 s", dict(t_dst=T2_6, window=6.0)),
        ("latency-10ms", "latency (stress)", "samples taken 10 ms before their stamps", dict(delay=0.01)),
        ("latency-20ms", "latency (stress)", "samples taken 20 ms before their stamps", dict(delay=0.02)),
        ("latency-minus-10ms", "latency (stress)", "samples taken 10 ms after their stamps", dict(delay=-0.01)),
        ("manoeuvre-stop", "manoeuvre (stress)", "acceleration 2 → 0 m/s² at 20 s", dict(a_after=0.0)),
        ("manoeuvre-reverse", "manoeuvre (stress)", "acceleration 2 → −2 m/s² at 20 s", dict(a_after=-2.0)),
        ("manoeuvre-stop-tuned", "manoeuvre (stress)", "2 → 0 m/s² at 20 s, q_v = 1, q_a = 0.1",
         dict(a_after=0.0, q_v=1.0, q_a=0.1)))]
