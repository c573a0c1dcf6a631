"""Chapter 07 (time registration, Shi, Suo & Ma 2023): the Monte-Carlo study the ledger reads.

Computed once per seed and run count (:func:`cached_study`), with the methods, noise levels and
unmodelled changes it runs.
"""

from __future__ import annotations

import dataclasses
from collections.abc import Mapping
from dataclasses import dataclass
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from fusion._counts import general
from fusion._frozen import constant
from fusion._results import ResultSpec, array, dict_of, instance, number, real_key, validated_post_init
from fusion._shown import shown
from fusion.book.study_cache import study_cache
from fusion.book.chapters.time_registration import _least_squares_windows, _record_times, _scenario_instants
from fusion.book.chapters.time_registration import (CAUSAL_IMPROVED, FIG4, IMPROVED, S3_READINGS, TWO,
                                                    robustness_readings)
from fusion.scenarios import time_registration as sc
from fusion.scenarios.time_registration import RegMethod

__all__ = [
    "S3",
    "EXTRAP",
    "LOCAL_QLS",
    "RegistrationStudy",
    "FIXED_LAG",
    "QLS",
    "study",
    "cached_study",
    "PRIMARY_SIGMA",
    "STRESS",
    "UNREGISTERED",
    "unregistered_runs",
]


S3 = RegMethod.KALMAN_PREDICT
EXTRAP = RegMethod.TWO_POINT_EXTRAPOLATION
FIXED_LAG = RegMethod.FIXED_LAG
QLS = RegMethod.QLS_NEXT
LOCAL_QLS = RegMethod.LOCAL_QLS
MSE = "registration MSE (m²)"
#: The §3 filter as the text describes it: the filter period changed at every registration instant.
PC: dict[str, object] = {"period_change": True}

#: The unmodelled changes every compared method is run under (rule R6): key -> monte_carlo keywords.
STRESS: dict[str, dict[str, object]] = constant({
    "manoeuvre-stop": {"a_after": 0.0},
    "manoeuvre-reverse": {"a_after": -2.0},
    "latency-10ms": {"delay": 0.01},
    "latency-minus-10ms": {"delay": -0.01},
})

#: Noise levels of the readings (m), besides the primary σ.
SIGMAS_ALT: tuple[float, ...] = (0.1, 0.3, 3.0, 10.0)

#: Methods run in every noise-level and stress study.
STUDY_METHODS: tuple[RegMethod, ...] = (
    TWO, IMPROVED, RegMethod.THREE_POINT, RegMethod.LEAST_SQUARES, EXTRAP, S3, CAUSAL_IMPROVED,
    RegMethod.THREE_POINT_EXTRAPOLATION, RegMethod.KALMAN_TWO_POINT, FIXED_LAG, QLS, LOCAL_QLS,
    RegMethod.QLS_CAUSAL, RegMethod.RTS_SMOOTHER, RegMethod.CUBIC_SPLINE)


#: Sensor 1's last sample taken as simultaneous with the instant (no registration).
UNREGISTERED = "no registration (sensor 1's last sample)"



@dataclass(frozen=True)
class RegistrationStudy:
    """Every Monte-Carlo study chapter 07's ledger reads (:func:`study`), each reading at the primary's runs (rule R4).

    Attributes
    ----------
    t1, t2 : ndarray
        The sample times and registration instants the study ran on (s).
    sigma : float
        The noise level of its primary runs (m).
    mc : MonteCarlo
        Every method of ``STUDY_METHODS``, the primary runs.
    sweep : dict of float to MonteCarlo
        Noise level σ of ``SIGMAS_ALT`` -> runs of every method.
    stress : dict of str to MonteCarlo
        Key of :data:`STRESS` -> runs of every method.
    robust : dict of str to MonteCarlo
        Key of :func:`~fusion.book.chapters.time_registration.robustness_readings` -> runs of the Fig. 4 methods.
    s3 : dict of str to MonteCarlo
        Key of :data:`~fusion.book.chapters.time_registration.S3_READINGS` -> runs of the §3 method and two-point
        extrapolation.
    s3_fair : dict of float to MonteCarlo
        σ -> §3, three-point extrapolation and least squares from the second instant.
    s3_period : MonteCarlo
        The §3 method with the period changed, on the primary runs.
    s3_pc : dict of str to MonteCarlo
        The §3 method with the period changed and two-point extrapolation on the runs of each noise level and
        stress test (and the tuned stop, ``"manoeuvre-stop-tuned"``).
    realtime : MonteCarlo
        Causal improved and two-point extrapolation from the second instant.
    stress_tuned : MonteCarlo
        The stop of the acceleration with q_v = 1, q_a = 0.1.
    cv_integer : MonteCarlo
        A constant-velocity target, sensor 2 every 6 s: where Blair's least squares is designed for.
    fusion : FusionRuns or None
        The fusion runs of :func:`cached_study` (``None`` from :func:`study`).
    """

    t1: np.ndarray
    t2: np.ndarray
    sigma: float
    mc: sc.MonteCarlo
    sweep: Mapping[float, sc.MonteCarlo]
    stress: Mapping[str, sc.MonteCarlo]
    robust: Mapping[str, sc.MonteCarlo]
    s3: Mapping[str, sc.MonteCarlo]
    s3_fair: Mapping[float, sc.MonteCarlo]
    s3_period: sc.MonteCarlo
    s3_pc: Mapping[str, sc.MonteCarlo]
    realtime: sc.MonteCarlo
    stress_tuned: sc.MonteCarlo
    cv_integer: sc.MonteCarlo
    fusion: sc.FusionRuns | None = None

    __result_spec__ = ResultSpec(
        {"t1": array("samples"), "t2": array("instants"), "sigma": number(positive=True),
         **{name: instance(sc.MonteCarlo) for name in ("mc", "s3_period", "realtime", "stress_tuned", "cv_integer")},
         # the evidence keys their readings by f"{s:g}" (_key): two levels printing alike would share one (fuzz 30b)
         # noise levels σ > 0, as the study's sigma (fuzz 32b D2: NaN, inf, -1 were accepted)
         **{name: dict_of(instance(sc.MonteCarlo), key=(float, int, np.number), printed=general,
                          check_key=real_key(0.0, lo_open=True)) for name in ("sweep", "s3_fair")},
         **{name: dict_of(instance(sc.MonteCarlo)) for name in ("stress", "robust", "s3", "s3_pc")},
         "fusion": instance(sc.FusionRuns, optional=True)},
        relations=(lambda v, cls: _robust_relation(v, cls),))
    __post_init__ = validated_post_init


def _robust_relation(values: Mapping[str, Any], cls: str) -> None:
    """``robust`` holds the runs of every robustness reading at the study's ``sigma`` and ``t2`` (the tables read
    each)."""
    want = {rd.key for rd in robustness_readings(values["sigma"], values["t2"])}
    if not want <= set(values["robust"]):
        raise ValueError(f"{cls}.robust must hold the runs of every robustness reading, misses "
                         f"{shown(sorted(want - set(values['robust'])))}")
    # each reading's runs hold the methods its readers compare, at the study's noise (fuzz 26d E1: a KeyError later)
    methods = (*FIG4, RegMethod.LEAST_SQUARES)
    for key, m in values["robust"].items():
        lacking = [str(x) for x in methods if x not in m.per_run]
        if lacking:
            raise ValueError(f"{cls}.robust[{shown(key)}] must hold the runs of {[str(x) for x in methods]}, "
                             f"lacks {lacking}")
        if m.sigma != values["sigma"]:
            raise ValueError(f"{cls}.robust[{shown(key)}] holds runs at sigma = {m.sigma:g}, not the study's "
                             f"{cls}.sigma = {values['sigma']:g}")


# the robustness tables take this study; their module cannot import it (this module imports the chapter module, which
# imports theirs): named there once it exists, so that typing.get_type_hints resolves their annotations
from fusion.book.chapters import time_registration_robustness as _robustness  # noqa: E402
from fusion._counts import seed as check_seed
from fusion._counts import count
from fusion._validation import std_scalar
from fusion._limits import work
from fusion.book._study_budget import studies_first

_robustness.RegistrationStudy = RegistrationStudy  # type: ignore[attr-defined]


def unregistered_runs(m: sc.MonteCarlo, t1: ArrayLike, t2: ArrayLike) -> np.ndarray:
    """Per-run MSE (m²) of taking sensor 1's last sample as simultaneous, on the very runs of ``m``.

    The noisy samples are drawn again exactly as :func:`fusion.scenarios.time_registration.monte_carlo` draws
    them (``default_rng(m.seed)``, the source's truth, no latency), so the runs are paired with ``m``'s.

    Parameters
    ----------
    m : MonteCarlo
        Runs on the source's truth at the default instants.
    t1, t2 : array_like
        Sample times and instants (s).

    Returns
    -------
    ndarray, shape (m.runs,)
        Per run, the mean over sensor 2's instants of the squared error of sensor 1's last sample (m², 10 decimals).

    Raises
    ------
    TypeError
        ``m`` is not a MonteCarlo, or ``t1``/``t2`` not numeric.
    ValueError
        ``t1`` or ``t2`` is not strictly increasing and finite, or so far from the flight's start that the true
        positions lose the precision of the errors (about 6e4 s at the source's sampling), or an instant of ``t2``
        precedes ``t1[0]`` (it has no last sample).
    """
    from fusion._validation import as_times, instance_of

    instance_of(m, sc.MonteCarlo, "m")
    t1, t2 = as_times(t1, "t1"), as_times(t2, "t2")
    sc._precise_times(t1, t2, "t1", "t2")  # times whose positions lose the precision (fuzz 24d C): named
    if t2[0] < t1[0]:
        raise ValueError(f"t2 must not precede sensor 1's first sample t1[0] = {t1[0]:g} s (no last sample), "
                         f"got t2[0] = {t2[0]:g} s")
    z = sc.truth(t1) + m.sigma * np.random.default_rng(m.seed).standard_normal((m.runs, t1.size))
    last = np.searchsorted(t1, t2, side="right") - 1
    return np.round(np.mean((z[:, last] - sc.truth(t2)) ** 2, axis=1), 10)


#: The noise level (m) of the fair §3 reading beside the study's own ``sigma``.
_FAIR_SIGMA = 0.1


def _key(s: float) -> str:
    """Reading key of a noise level: ``sigma-0-1`` for 0.1 m."""
    return "sigma-" + f"{s:g}".replace(".", "-")


#: The work of :func:`study` in Monte Carlos of every method of ``STUDY_METHODS`` on the scenario's samples (rule 17):
#: measured 10.4 CPU-s for the study at 1e5 runs against 0.56 s for one such Monte Carlo, about 19 of them.
_STUDY_CALLS = 19
#: Units of one run of one such Monte Carlo over one sample and method (12 to 16 ns measured at 5,000 and 20,000
#: runs: 2 units of ``fusion._limits.MAX_WORK``'s 10 ns; fuzz 30b D2).
_STUDY_WEIGHT = 2


#: The methods of :func:`study`'s robustness readings (Fig. 4's and least squares) and of its fair §3 readings.
_FIG4_ROBUST = list(FIG4) + [RegMethod.LEAST_SQUARES]
_FAIR = [S3, RegMethod.THREE_POINT_EXTRAPOLATION, RegMethod.LEAST_SQUARES]


def _study_work(runs: int, n_dst: int, names: str, readings: str, times: str) -> int:
    """Rule 17 of :func:`study` on ``runs`` runs and ``n_dst`` instants of ``t2``, before its first run; its units.

    The whole study (fuzz 26d DB6: each Monte Carlo within the budget, the study ran minutes), measured as
    ``_STUDY_CALLS`` Monte Carlos of every study method (10.4 CPU-s at 1e5 runs, one of them 0.56 s), refused from
    about 8.8e4 runs (the chapter runs 1,000), naming ``names``; and the readings on ``t2``'s instants (the start-up,
    fair and real-time ones), by ``monte_carlo``'s own rule (fuzz 28b C4: t2 was not counted, 20,000 instants ran
    17 s at 2 runs, refused inside as ``t_dst``), naming ``readings`` (their runs) or ``times``.
    """
    units = work((runs, sc.instants()[0].size, len(STUDY_METHODS), _STUDY_CALLS), names, weight=_STUDY_WEIGHT)
    sc._monte_carlo_work(_FIG4_ROBUST + 2 * _FAIR + [CAUSAL_IMPROVED, EXTRAP], runs, sc.instants()[0].size, n_dst,
                         readings, times)
    return units


def _seed_span(n_robust: int) -> int:
    """The largest offset :func:`study` adds to its seed (its readings' ``seed + 100 + i`` .. ``seed + 180``), with
    ``n_robust`` robustness readings."""
    return max(100 + len(SIGMAS_ALT), 110 + len(STRESS), 120 + n_robust, 140 + len(S3_READINGS), 152, 181) - 1


def study(t1: ArrayLike, t2: ArrayLike, sigma: float, runs: int, seed: int) -> RegistrationStudy:
    """Every Monte-Carlo study the ledger needs, each reading at the primary's ``runs`` (rule R4).

    Parameters
    ----------
    t1, t2 : array_like
        Sensor-1 sample times and sensor-2 instants (s), kept in the result for the evidence; the runs are on the
        scenario's sensor-1 samples, and the fair, real-time and start-up readings register ``t2[1:]`` or
        ``t2[2:]`` onto them (so ``t2`` holds three instants at least, within their record).
    sigma : float
        Primary noise level (m).
    runs : int
        Runs of the primary and of every reading.
    seed : int
        Seed of the primary runs (``seed``); the readings use ``seed + 100 + i``.

    Returns
    -------
    RegistrationStudy
        The primary runs of every method of ``STUDY_METHODS`` and every reading's runs (without ``fusion``).

    Raises
    ------
    TypeError
        ``t1`` or ``t2`` not numeric, ``sigma`` not a number, ``runs`` or ``seed`` not an integer.
    ValueError
        ``t1`` or ``t2`` not finite strictly increasing 1-D times (``t1``: three samples at least), an instant of
        ``t2`` outside the record of ``t1`` or of the scenario's sensor-1 samples (the readings register ``t2``
        onto these), ``t2`` of fewer than three instants (the start-up reading scores ``t2[2:]``) or with fewer
        than two of those samples in the least-squares window before an instant, times so far from the flight's
        start that the positions lose the precision (about 6e4 s), ``sigma`` not a valid standard deviation (or
        within 6 significant digits of 0.1 m without being it: the fair reading's levels are keyed as printed),
        ``runs`` below 1 or beyond the work budget (``fusion._limits.MAX_WORK``: about 8.8e4 runs; ``t2``'s instants
        counted too, as :func:`~fusion.scenarios.time_registration.monte_carlo` counts its ``t_dst``: 2,000 instants
        are refused), ``seed`` negative.
    """
    seed = check_seed(seed)
    # the arguments read before any run (an unchecked one escaped as numpy's error, or was stored as given)
    t1, t2 = _record_times(t1, t2)  # increasing, within the record of t1, positions precise (fuzz 24d C): named
    # the readings register t2[1:] and t2[2:] onto the scenario's samples (fuzz 24d W: refused inside by
    # monte_carlo's names): three instants within their record, two samples in each least-squares window
    _least_squares_windows(sc.instants()[0], _scenario_instants(t2, 3, "the start-up reading scores from the third"))
    sigma, runs = std_scalar(sigma, "sigma"), count(runs, "runs")
    seed = check_seed(seed, span=_seed_span(len(robustness_readings(sigma, t2))))   # fuzz 55 D1
    if sigma != _FAIR_SIGMA and general(sigma) == general(_FAIR_SIGMA):  # s3_fair's readings keyed by _key (fuzz 30b)
        raise ValueError(f"sigma must be {_FAIR_SIGMA:g} m or differ from it to 6 significant digits (the fair §3 "
                         f"reading at {_FAIR_SIGMA:g} m and at sigma are keyed by the printed level)")
    _study_work(runs, t2.size, "runs", "runs and t2", "t2")
    names = list(STUDY_METHODS)
    fig4, fair = list(_FIG4_ROBUST), list(_FAIR)
    return RegistrationStudy(
        t1=t1, t2=t2, sigma=float(sigma),
        mc=sc.monte_carlo(names, sigma, runs, seed),
        sweep={s: sc.monte_carlo(names, s, runs, seed + 100 + i) for i, s in enumerate(SIGMAS_ALT)},
        stress={k: sc.monte_carlo(names, sigma, runs, seed + 110 + i, **kw)  # type: ignore[arg-type]
                for i, (k, kw) in enumerate(STRESS.items())},
        robust={rd.key: sc.monte_carlo(fig4, sigma, runs, seed + 120 + i, **rd.options)  # type: ignore[arg-type]
                for i, rd in enumerate(robustness_readings(sigma, t2))},
        s3={k: sc.monte_carlo([S3, EXTRAP], sigma, runs, seed + 140 + i, kf={**kw, **PC})
            for i, (k, _, _, kw) in enumerate(S3_READINGS) if k != "per-step-period-changed"},
        s3_fair={s: sc.monte_carlo(fair, s, runs, seed + 150 + i, t_dst=t2[1:], kf=PC)
                 for i, s in enumerate((_FAIR_SIGMA, float(sigma)))},
        s3_period=sc.monte_carlo([S3], sigma, runs, seed, kf=PC),
        # §3 as the text describes it (period changed), on the very runs of the sweep and of the stress tests
        s3_pc={**{_key(s): sc.monte_carlo([S3, EXTRAP], s, runs, seed + 100 + i, kf=PC)
                  for i, s in enumerate(SIGMAS_ALT)},
               **{k: sc.monte_carlo([S3, EXTRAP], sigma, runs, seed + 110 + i, kf=PC, **kw)  # type: ignore[arg-type]
                  for i, (k, kw) in enumerate(STRESS.items())},
               "manoeuvre-stop-tuned": sc.monte_carlo([S3, EXTRAP], sigma, runs, seed + 170, kf=PC, a_after=0.0,
                                                      q_v=1.0, q_a=0.1)},
        realtime=sc.monte_carlo([CAUSAL_IMPROVED, EXTRAP], sigma, runs, seed + 160, t_dst=t2[1:]),
        stress_tuned=sc.monte_carlo([IMPROVED, TWO, S3, EXTRAP, FIXED_LAG], sigma, runs, seed + 170,
                                    a_after=0.0, q_v=1.0, q_a=0.1),
        cv_integer=sc.monte_carlo([TWO, EXTRAP, RegMethod.LEAST_SQUARES], sigma, runs, seed + 180,
                                  t_dst=sc.instants(6.0)[1], window=6.0, a_after=0.0, t_change=0.0),
    )


#: Noise level of the primary readings (m): the source gives none.
PRIMARY_SIGMA = 1.0


@study_cache(maxsize=2)
def cached_study(seed: int, runs: int) -> RegistrationStudy:
    """:func:`study` of the source's scenario at :data:`PRIMARY_SIGMA`, with the fusion runs (seed ``seed + 49``),
    computed once per ``(seed, runs)``: the chapter and every evidence function share it.

    Parameters
    ----------
    seed, runs : int
        As in :func:`study`.

    Returns
    -------
    RegistrationStudy
        :func:`study`'s result with ``fusion`` (:func:`fusion.scenarios.time_registration.fusion_runs` of the
        improved method, two-point interpolation, the §3 prediction and least squares).
    """
    t1, t2 = sc.instants()
    # its study's seeds and the fusion runs' seed + 49, each a seed, checked at entry (fuzz 55 D1: refused after ~2.4
    # CPU-s of work, naming a 257-bit seed)
    seed = check_seed(seed, span=max(49, _seed_span(len(robustness_readings(PRIMARY_SIGMA, t2)))))
    fused = [IMPROVED, TWO, S3, RegMethod.LEAST_SQUARES]
    # rule 17 on the study and the fusion runs together, before either (fuzz 54a C4: the study's own check passed up
    # to 87,719 runs, then fusion_runs refused beyond 20,000 after the study ran, 8-10 CPU-s): each by its own budget
    # function, summed
    runs = count(runs, "runs")
    studies_first([lambda: _study_work(runs, t2.size, "runs", "runs", "runs"),
                   lambda: sc._fusion_runs_work(fused, runs, t1.size, t2.size, "runs", "runs")], "runs")
    st = study(t1, t2, PRIMARY_SIGMA, runs, seed)
    return dataclasses.replace(st, fusion=sc.fusion_runs(fused, PRIMARY_SIGMA, runs,
                                                         seed + 49))
