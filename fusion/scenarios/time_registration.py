r"""The drone time-registration case of Shi, Suo & Ma (2023, §5) and its Monte-Carlo study.

A drone starts at the origin with 1 m/s due east and accelerates at 2 m/s² (direction not
stated; east taken) for 40 s: :math:`x(t) = v_0 t + \tfrac12 a t^2`, :math:`y \equiv 0`.
Sensor 1 samples every 2 s from 1 s, sensor 2 every 5 s from 3 s; sensor 1 is registered onto
sensor 2's instants. Every method of the chapter is keyed by :class:`RegMethod` (display labels in
:data:`fusion.book.style.METHOD_LABELS`) and listed in :data:`METHODS` with the information it uses at a
registration instant, an :class:`Information` key: causal (samples not later than the instant, usable in real
time), look-ahead (also the next sample, offline) or whole record.

:func:`monte_carlo` *runs* every method on noisy samples (no linear decomposition), so its
per-run MSEs can be compared, paired, with the exact expectation of :func:`expected`.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum
from functools import partial, wraps
from typing import Any

import numpy as np
from numpy.typing import ArrayLike

from fusion._frozen import constant
from fusion._results import NONNEGATIVE, ResultSpec, array, dict_of, integer, number, validated_post_init
from fusion import registration as reg
from fusion.registration import methods as _methods
from fusion.scenarios._time_registration_work import (_exact_work, _fusion_runs_work, _monte_carlo_work,  # noqa: F401
                                                      _registration_work, MC_NAME_UNITS)
from fusion._limits import LOOP_STEP, work
from fusion.scenarios import _time_registration_kf as _kf
from fusion._validation import read_mapping, read_once
from fusion._validation import derived_inputs
from fusion._validation import shown
from fusion._validation import text
from fusion._validation import as_times, seed as check_seed
from fusion._validation import (FloatArray, as_array, count, nonnegative_scalar, positive_scalar, same_length, scalar,
                                sequence, std_scalar, grid_points)
from fusion.data import SHI2023_SCENARIO

__all__ = [
    "RegMethod",
    "Information",
    "SCENARIO",
    "METHODS",
    "SAME_INFORMATION",
    "FILTER_METHODS",
    "Q_V",
    "Q_A",
    "KF_OPTIONS",
    "truth",
    "manoeuvre_truth",
    "instants",
    "register",
    "registrar",
    "expected",
    "two_point_remainder",
    "noise_free_mse",
    "noise_gain",
    "crossing_sigma",
    "MonteCarlo",
    "monte_carlo",
    "mse_coefficients",
    "FusionRuns",
    "fusion_runs",
]


class RegMethod(StrEnum):
    """Method keys of the chapter; display labels in :data:`fusion.book.style.METHOD_LABELS`.

    Attributes
    ----------
    TWO_POINT
        Two-point interpolation between the samples either side of the instant.
    LEAST_SQUARES
        Linear least squares on the samples of the last sensor-2 period (causal).
    THREE_POINT
        Three-point (quadratic) interpolation through the samples around the instant.
    KALMAN_PREDICT
        The Kalman filter's state predicted to the instant (§3).
    KALMAN_TWO_POINT
        Two-point interpolation of the filtered positions.
    IMPROVED
        The source's improved method: three-point interpolation of the filtered positions (§4).
    TWO_POINT_EXTRAPOLATION
        Two-point extrapolation from the last two samples (causal).
    CAUSAL_IMPROVED
        Three-point extrapolation of the filtered positions (causal).
    QLS_NEXT
        Quadratic least squares on every past sample and the next one.
    QLS_CAUSAL
        Quadratic least squares on every past sample (causal).
    THREE_POINT_EXTRAPOLATION
        Three-point extrapolation from the last three samples (causal).
    RTS_SMOOTHER
        The RTS smoother on the whole record, predicted to the instant.
    CUBIC_SPLINE
        A cubic spline through the whole record.
    FIXED_LAG
        The fixed-lag smoother using the next sample, predicted to the instant.
    LOCAL_QLS
        Quadratic least squares on the last four samples and the next one.
    """

    TWO_POINT = "reg_two_point"
    LEAST_SQUARES = "reg_least_squares"
    THREE_POINT = "reg_three_point"
    KALMAN_PREDICT = "reg_kalman_predict"
    KALMAN_TWO_POINT = "reg_kalman_two_point"
    IMPROVED = "reg_improved"
    TWO_POINT_EXTRAPOLATION = "reg_two_point_extrapolation"
    CAUSAL_IMPROVED = "reg_causal_improved"
    QLS_NEXT = "reg_qls_next"
    QLS_CAUSAL = "reg_qls_causal"
    THREE_POINT_EXTRAPOLATION = "reg_three_point_extrapolation"
    RTS_SMOOTHER = "reg_rts_smoother"
    CUBIC_SPLINE = "reg_cubic_spline"
    FIXED_LAG = "reg_fixed_lag"
    LOCAL_QLS = "reg_local_qls"


class Information(StrEnum):
    """Keys of the information a method uses at a registration instant (:data:`METHODS`); display labels in
    :data:`fusion.book.style.METHOD_LABELS`.

    Attributes
    ----------
    CAUSAL
        Only samples not later than the instant (usable in real time).
    LOOK_AHEAD
        Also the next sample (offline).
    WHOLE_RECORD
        Every sample of the record (offline).
    """

    CAUSAL = "reg_info_causal"
    LOOK_AHEAD = "reg_info_look_ahead"
    WHOLE_RECORD = "reg_info_whole_record"


#: The scenario of §5 (identical in simulations 1-3).
SCENARIO = SHI2023_SCENARIO

#: Default per-step disturbance variances of the Kalman filter (m²/s², m²/s⁴); the source gives none.
Q_V, Q_A = 1e-2, 1e-3

#: Every registration method of the chapter and the information it uses at an instant t_k.
METHODS: dict[RegMethod, Information] = constant({
    RegMethod.TWO_POINT: Information.LOOK_AHEAD,
    RegMethod.LEAST_SQUARES: Information.CAUSAL,
    RegMethod.THREE_POINT: Information.LOOK_AHEAD,
    RegMethod.KALMAN_PREDICT: Information.CAUSAL,
    RegMethod.KALMAN_TWO_POINT: Information.LOOK_AHEAD,
    RegMethod.IMPROVED: Information.LOOK_AHEAD,
    RegMethod.TWO_POINT_EXTRAPOLATION: Information.CAUSAL,
    RegMethod.CAUSAL_IMPROVED: Information.CAUSAL,
    RegMethod.QLS_NEXT: Information.LOOK_AHEAD,
    RegMethod.QLS_CAUSAL: Information.CAUSAL,
    RegMethod.THREE_POINT_EXTRAPOLATION: Information.CAUSAL,
    RegMethod.RTS_SMOOTHER: Information.WHOLE_RECORD,
    RegMethod.CUBIC_SPLINE: Information.WHOLE_RECORD,
    RegMethod.FIXED_LAG: Information.LOOK_AHEAD,
    RegMethod.LOCAL_QLS: Information.LOOK_AHEAD,
})

#: Look-ahead methods that use exactly the improved method's information (every past sample and the next one).
SAME_INFORMATION: tuple[RegMethod, ...] = (RegMethod.FIXED_LAG, RegMethod.QLS_NEXT, RegMethod.LOCAL_QLS)

#: Keys accepted in the ``kf`` options of :func:`register`, :func:`expected` and :func:`monte_carlo`:
#: ``q_model`` and ``init`` (see :func:`fusion.registration.methods.kalman_filter`), ``p0`` (initial
#: velocity and acceleration variances) and ``period_change`` (bool: the filter also steps to each
#: registration instant, the source's change of the filter period).
KF_OPTIONS: tuple[str, ...] = ("q_model", "init", "p0", "period_change")

_SMOOTHED = RegMethod.RTS_SMOOTHER
_LAGGED = RegMethod.FIXED_LAG
_STATES = {_SMOOTHED: "smoothed", _LAGGED: "lagged"}

#: The fixed-weight methods: key -> (registration function of :mod:`fusion.registration`, its options); the
#: least-squares window (option ``window``, ``None`` for sensor 2's period) comes from :func:`register`.
_DIRECT: dict[RegMethod, tuple[Callable[..., FloatArray], dict[str, Any]]] = {
    RegMethod.TWO_POINT: (reg.two_point, {}),
    RegMethod.TWO_POINT_EXTRAPOLATION: (reg.two_point, dict(causal=True)),
    RegMethod.LEAST_SQUARES: (reg.least_squares, {"window": None}),
    RegMethod.THREE_POINT: (reg.three_point, {}),
    RegMethod.QLS_NEXT: (reg.quadratic_ls, {"lookahead": 1}),
    RegMethod.THREE_POINT_EXTRAPOLATION: (reg.three_point, dict(causal=True)),
    RegMethod.QLS_CAUSAL: (reg.quadratic_ls, {"lookahead": 0}),
    RegMethod.LOCAL_QLS: (reg.quadratic_ls, {"lookahead": 1, "past": 4}),
    RegMethod.CUBIC_SPLINE: (reg.spline_register, {}),
}

#: The Kalman methods: key -> the fixed-weight method of :data:`_DIRECT` run on the filtered (or smoothed)
#: positions, or ``None`` to predict the states to the instant (:func:`fusion.registration.predict_to`).
_ON_STATES: dict[RegMethod, RegMethod | None] = {
    RegMethod.KALMAN_PREDICT: None,
    _SMOOTHED: None,
    _LAGGED: None,
    RegMethod.KALMAN_TWO_POINT: RegMethod.TWO_POINT,
    RegMethod.IMPROVED: RegMethod.THREE_POINT,
    RegMethod.CAUSAL_IMPROVED: RegMethod.THREE_POINT_EXTRAPOLATION,
}
#: The methods built on the Kalman filter (its filtered, smoothed or lagged states); the others have fixed weights.
FILTER_METHODS: frozenset[RegMethod] = frozenset(_ON_STATES)
_KALMAN = FILTER_METHODS
#: The methods whose registration is a Python loop over the instants (a fit per instant, ~12 us each here).
_PER_INSTANT = frozenset({RegMethod.LEAST_SQUARES, RegMethod.QLS_NEXT, RegMethod.QLS_CAUSAL, RegMethod.LOCAL_QLS})


def truth(t: ArrayLike) -> FloatArray:
    r"""True east position :math:`x(t) = v_0 t + \tfrac12 a t^2` (m) at times ``t`` (s), any shape.

    The UAV of Shi, Suo & Ma (2023): start at 0, :math:`v_0` = 1 m/s east, :math:`a` = 2 m/s²
    (``SCENARIO``).

    Parameters
    ----------
    t : array_like
        Times (s).

    Returns
    -------
    ndarray
        Positions (m), of the shape of ``t``.
    """
    t = read_once(t, "t")  # converted once, then checked and used (fuzz 29a C5)
    as_array(t, "t", nonempty=False)
    tt = np.asarray(t, dtype=float)
    return SCENARIO["v0"] * tt + 0.5 * SCENARIO["a"] * tt**2


def manoeuvre_truth(t: ArrayLike, a_after: float | None, t_change: float = 20.0) -> FloatArray:
    r"""True position (m) when the acceleration changes to ``a_after`` at ``t_change`` (a model-breaking truth).

    Up to ``t_change`` the trajectory is :func:`truth`; afterwards it continues from the position and
    velocity reached there with the constant acceleration ``a_after`` (m/s²). ``a_after=None`` returns
    :func:`truth` itself. The constant-acceleration Kalman filter of the chapter does not model the change.

    Parameters
    ----------
    t : array_like
        Times (s), any shape.
    a_after : float or None
        Acceleration after the change (m/s²); ``None`` for no change.
    t_change : float
        Time of the change (s).

    Returns
    -------
    ndarray
        Positions (m), of the shape of ``t``.

    References
    ----------
    Shi, Suo & Ma (2023) state a constant acceleration of 2 m/s²; the change is the book's robustness check.
    """
    t = read_once(t, "t")  # converted once, then checked and used (fuzz 29a C5)
    as_array(t, "t", nonempty=False)
    t_change = scalar(t_change, "t_change")  # checked also without a change (fuzz 24a D4: every option is checked)
    if a_after is None:
        return truth(t)
    a_after = scalar(a_after, "a_after")
    tt = np.asarray(t, dtype=float)
    x = truth(tt)
    dt = tt - t_change
    after = dt > 0
    xc = float(truth(t_change))
    vc = SCENARIO["v0"] + SCENARIO["a"] * t_change
    return np.where(after, xc + vc * dt + 0.5 * a_after * dt**2, x)


def instants(period_2: float | None = None) -> tuple[FloatArray, FloatArray]:
    """Sample times of sensor 1 and of sensor 2 (the registration instants) in the 40 s window.

    Parameters
    ----------
    period_2 : float, optional
        Sensor 2's period (s); default the source's 5 s. Sensor 1 keeps 2 s from 1 s.

    Returns
    -------
    t1 : ndarray, shape (n,)
        Sensor-1 sample times (s): 1, 3, ..., 39.
    t2 : ndarray, shape (K,)
        Sensor-2 sample times (s): 3, 8, ..., not later than 40.
    """
    p2 = SCENARIO["period_2"] if period_2 is None else positive_scalar(period_2, "period_2")
    grid_points(SCENARIO["duration"] - SCENARIO["on_2"], p2, "period_2")  # rule 9: refused by name
    t1 = reg.sample_times(SCENARIO["on_1"], SCENARIO["period_1"], SCENARIO["duration"])
    t2 = reg.sample_times(SCENARIO["on_2"], p2, SCENARIO["duration"])
    return t1, t2


def _times_named(fn: Callable[..., Any]) -> Callable[..., Any]:
    """Name ``t_src`` (and ``t_dst``) in the refusals of the methods' own series checks (issue 35, class 6).

    A method refuses a series too short for it (``t and z must hold at least 3 samples``) and a step
    between instants too large for its model (``dt = ... is too large``) by its own names, which are
    not the arguments of the scenario's entries: these two messages are re-raised naming them.
    """
    @wraps(fn)
    def call(*args: Any, **kwargs: Any) -> Any:
        try:
            return fn(*args, **kwargs)
        except ValueError as exc:
            msg = str(exc)
            if msg.startswith("t and z must hold"):
                method = args[0] if args else kwargs.get("name")
                raise ValueError(f"t_src must hold{msg[len('t and z must hold'):]} for method {shown(method)}") \
                    from None
            if msg.startswith("dt = "):
                raise ValueError(f"t_src and t_dst give a step that is refused: {msg}") from None
            raise
    return call


#: Largest rounding (m) of the true positions at the times, as a fraction of the closed forms' scale (see
#: :func:`_precise_times`).
_POSITION_ROUNDING = 1e-6


def _precise_times(t_src: ArrayLike, t_dst: ArrayLike, src: str = "t_src", dst: str = "t_dst") -> None:
    """Refuse, naming ``src`` and ``dst``, times so far from the flight's start that the positions lose the precision.

    The registration errors are differences of positions: the closed forms perturb one sample by 1 m
    (:func:`fusion.registration.analysis.affine_decomposition`), while the positions
    :math:`x(t) = v_0 t + a t^2/2` are rounded to :math:`\\epsilon\\max|x(t)|` (the float spacing). When that
    rounding exceeds 1e-6 of that 1 m, the differences cancel catastrophically (fuzz 24d C: at t + 1e8 s the
    two-point E[MSE] came out 0.0 instead of 1.25 m²); the scenario's times are measured from the flight's start at
    t = 0, where the truth is the UAV's, so such times are refused rather than shifted (the truth, the latency
    bounds and the manoeuvre's ``t_change`` are absolute). Times within about 6e4 s of the start pass, whatever the
    steps between them (fuzz 25 R1: a scale set by the smallest step refused two samples 1 ms apart at 39 s).
    """
    ts, td = np.asarray(t_src, dtype=float), np.asarray(t_dst, dtype=float)
    both = np.concatenate([ts.ravel(), td.ravel()])
    if both.size == 0:
        return
    far = float(np.max(np.abs(both)))
    rounding = float(np.finfo(float).eps) * float(np.max(np.abs(truth(both))))
    if not rounding <= _POSITION_ROUNDING:
        raise ValueError(
            f"{src} and {dst} reach {far:.6g} s from the flight's start (t = 0), where the true positions are rounded "
            f"to {rounding:.2g} m, more than {_POSITION_ROUNDING:g} of the 1 m the registration errors are measured "
            f"against: the errors, differences of those positions, would cancel; give times measured from the start "
            f"of the flight")


def _check_args(t_src: ArrayLike, t_dst: ArrayLike, sigma: float, q_v: float, q_a: float) -> tuple[float, float, float]:
    """Validate the times and the Kalman tuning shared by :func:`register` and :func:`registrar`; return ``sigma``,
    ``q_v`` and ``q_a`` as the floats read, which the callers compute with (fuzz 22b, FR: never a Decimal)."""
    as_times(t_src, "t_src")
    as_times(t_dst, "t_dst")
    return std_scalar(sigma, "sigma"), nonnegative_scalar(q_v, "q_v"), nonnegative_scalar(q_a, "q_a")


def _delay_bounds(t1: FloatArray, t2: FloatArray) -> tuple[float, float]:
    """The latencies (s) that keep sensor 1's true sample times ``t1 - delay`` in the flight: from its start at 0 to
    the end of the record (``SCENARIO["duration"]``, or the last stamp if later), where the truth is the UAV's
    (:func:`truth` starts at 0 at t = 0). ``(-1, 1)`` for the source's sampling."""
    end = max(float(SCENARIO["duration"]), float(t1[-1]), float(t2[-1]))
    return float(t1[-1]) - end, float(t1[0])


def _check_name(name: str, arg: str = "name") -> str:
    """A method name of :data:`METHODS` as its plain text (rule 19), refused under ``arg`` (the caller's path)."""
    if not isinstance(name, str):
        raise TypeError(f"{arg} must be a method name (str), got {type(name).__name__}")
    name = text(name, arg)  # rule 19: a str subclass whose own comparison disagrees with its text is refused
    if name not in METHODS:
        raise ValueError(f"{arg} must be a RegMethod key, one of {sorted(METHODS)}, got {shown(name)}")
    return name


def _kf_kwargs(kf: Mapping[str, Any] | None, t_dst: FloatArray) -> dict[str, Any]:
    """Translate the chapter's ``kf`` options into :func:`fusion.registration.methods.kalman_runs` keywords."""
    return _kf.kf_kwargs(kf, t_dst, KF_OPTIONS)


def _filtered(names: Sequence[str], t_src: FloatArray, Z: FloatArray, t_dst: FloatArray, sigma: float,
              q_v: float, q_a: float, kf: Mapping[str, Any] | None) -> dict[str, FloatArray | None]:
    """Filtered (and, if needed, smoothed) states of every run, shared by the Kalman methods."""
    kw = _kf_kwargs(kf, t_dst)
    out: dict[str, FloatArray | None] = {"filtered": None, "smoothed": None, "lagged": None}
    if any(n in _KALMAN and n not in _STATES for n in names):
        out["filtered"] = reg.kalman_runs(t_src, Z, sigma, q_v, q_a, **kw).x
    if _SMOOTHED in names:
        out["smoothed"] = reg.kalman_runs(t_src, Z, sigma, q_v, q_a, smooth=True, **kw).x
    if _LAGGED in names:
        out["lagged"] = reg.kalman_runs(t_src, Z, sigma, q_v, q_a, lag_one=True, **kw).x
    return out


def _options(kf: Mapping[str, Any] | None, window: float | None,
             t_dst: ArrayLike) -> tuple[Mapping[str, Any] | None, float | None]:
    """Check the filter options and the least-squares window whatever the method (fuzz 24a D4: an option the
    chosen method does not use is still the caller's, and a bad one is refused by name); ``kf`` read once (a
    caller's mapping that is not a dict becomes the dict checked and used, ``fusion._guards.read_mapping``) and the
    window as given."""
    kf = read_mapping(kf, "kf")
    _kf_kwargs(kf, np.asarray(t_dst, dtype=float))
    return kf, None if window is None else positive_scalar(window, "window")


def _direct(name: str, t_src: ArrayLike, z: ArrayLike, t_dst: ArrayLike, window: float | None = None) -> FloatArray:
    """A fixed-weight method of :data:`_DIRECT` on one sample vector."""
    fn, options = _DIRECT[name]
    if "window" in options:
        options = {**options, "window": SCENARIO["period_2"] if window is None else window}
    return fn(t_src, z, t_dst, **options)


def _from_filtered(name: str, t_src: FloatArray, xs: FloatArray, t_dst: FloatArray) -> FloatArray:
    """A Kalman method of :data:`_ON_STATES` from the states (n, 3) of one run."""
    base = _ON_STATES[name]
    if base is None:
        return reg.predict_to(t_src, xs, t_dst)
    return _direct(base, t_src, xs[:, 0], t_dst)


@_times_named
def register(name: str, t_src: ArrayLike, z: ArrayLike, t_dst: ArrayLike, sigma: float,
             q_v: float = Q_V, q_a: float = Q_A, *, kf: Mapping[str, Any] | None = None,
             window: float | None = None) -> FloatArray:
    """Register sensor-1 samples onto sensor-2 instants with one method of :data:`METHODS`.

    Parameters
    ----------
    name : str
        A key of :data:`METHODS`.
    t_src, z : array_like, shape (n,)
        Sensor-1 sample times (s) and measured positions (m).
    t_dst : array_like, shape (K,)
        Registration instants (s).
    sigma : float
        Measurement-noise standard deviation the Kalman filter assumes (m); unused otherwise.
    q_v, q_a : float
        Per-step disturbance variances of the Kalman filter (eq. 3, rebuilt).
    kf : mapping, optional
        Further filter options, keys :data:`KF_OPTIONS`.
    window : float, optional
        Least-squares window (s); default sensor 2's period in the source, 5 s. Checked, as ``kf`` is, whatever
        the method, also one that does not use it.

    Returns
    -------
    ndarray, shape (K,)
        Registered positions (m).

    Raises
    ------
    ValueError
        Among others, a Kalman method's filter beyond the work budget (its steps: the samples, and with
        ``period_change`` every instant), naming ``t_src``, ``z`` (and ``t_dst``) before the filter (fuzz 53b C4).
    """
    t_src, z, t_dst = (read_once(t_src, "t_src"), read_once(z, "z"), read_once(t_dst, "t_dst"))
    name = _check_name(name)
    sigma, q_v, q_a = _check_args(t_src, t_dst, sigma, q_v, q_a)
    same_length(as_array(t_src, "t_src", ndim=1), "t_src", as_array(z, "z", ndim=1), "z")
    kf, window = _options(kf, window, t_dst)
    if name in _DIRECT:
        return _direct(name, t_src, z, t_dst, window)
    ts, td = np.asarray(t_src, dtype=float), np.asarray(t_dst, dtype=float)
    # rule 17, named here (fuzz 53b C4): the filter's grid is the samples and, with period_change, at most the instants
    extra = bool(kf and kf.get("period_change", False))
    smoothed = name in (_SMOOTHED, _LAGGED) or bool(kf and kf.get("smooth", False))
    _methods._kalman_work(ts.size + (td.size if extra else 0), 1, smoothed,
                          "t_src, z and t_dst" if extra else "t_src and z")
    states = _filtered([name], ts, np.asarray(z, dtype=float), td, sigma, q_v, q_a, kf)
    return _from_filtered(name, ts, states[_STATES.get(name, "filtered")], td)


def registrar(name: str, t_src: ArrayLike, t_dst: ArrayLike, sigma: float,
              q_v: float = Q_V, q_a: float = Q_A, *, kf: Mapping[str, Any] | None = None,
              window: float | None = None) -> partial[FloatArray]:
    """:func:`register` with everything but the samples fixed: a map ``z -> registered values``.

    Parameters
    ----------
    name : str
        Registration method (as in :func:`register`).
    t_src : array_like, shape (n,)
        Sample times of the fast sensor (s).
    t_dst : array_like, shape (K,)
        Registration instants (s).
    sigma : float
        Measurement-noise standard deviation (m) given to the Kalman methods.
    q_v, q_a : float
        Kalman driving-noise variances (see :func:`fusion.registration.methods.kalman_filter`).
    kf : mapping, optional
        Further filter options (:data:`KF_OPTIONS`).
    window : float, optional
        Least-squares window (s). Checked, as ``kf`` is, whatever the method, also one that does not use it.

    Returns
    -------
    functools.partial
        Callable of the samples ``z`` (shape (n,)) returning the registered values (shape (K,)),
        as :func:`fusion.registration.analysis.affine_decomposition` needs.

    Raises
    ------
    ValueError
        Unknown ``name``.
    """
    t_src, t_dst = (read_once(t_src, "t_src"), read_once(t_dst, "t_dst"))  # converted once (fuzz 29a C5)
    name = _check_name(name)
    sigma, q_v, q_a = _check_args(t_src, t_dst, sigma, q_v, q_a)
    kf, window = _options(kf, window, t_dst)
    return partial(_registrar_call, name, np.asarray(t_src, dtype=float), np.asarray(t_dst, dtype=float),
                   sigma, q_v, q_a, kf, window)


def _registrar_call(name: str, t_src: FloatArray, t_dst: FloatArray, sigma: float, q_v: float, q_a: float,
                    kf: Mapping[str, Any] | None, window: float | None, z: ArrayLike) -> FloatArray:
    return register(name, t_src, z, t_dst, sigma, q_v, q_a, kf=kf, window=window)


@_times_named
def expected(name: str, sigma: float, t_src: ArrayLike | None = None, t_dst: ArrayLike | None = None,
             q_v: float = Q_V, q_a: float = Q_A, *, kf: Mapping[str, Any] | None = None,
             window: float | None = None, sigma_filter: float | None = None, delay: float = 0.0,
             a_after: float | None = None, t_change: float = 20.0) -> float:
    r"""Exact expected registration MSE (m²) of one method under white noise ``sigma`` (eq. reg-mse).

    :math:`E[\mathrm{MSE}] = \frac1K\sum_k (b_k^2 + \sigma^2\lVert a_k\rVert^2)` by superposition
    (:func:`fusion.registration.analysis.expected_mse`); the Kalman filter assumes the true ``sigma``.

    Parameters
    ----------
    name : str
        A key of :data:`METHODS`.
    sigma : float
        Measurement-noise standard deviation (m), > 0.
    t_src, t_dst : array_like, optional
        Sample times and instants (s); default :func:`instants`. Refused, named, so far from the flight's start
        (t = 0) that the true positions lose the precision of the errors (``_precise_times``: about 6e4 s). Their
        sizes are held to the work budget, refused by name before any work (``_registration_work``).
    q_v, q_a : float
        Kalman tuning.
    kf : mapping, optional
        Further filter options (:data:`KF_OPTIONS`).
    window : float, optional
        Least-squares window (s). Checked, as ``kf`` is, whatever the method, also one that does not use it.
    sigma_filter : float, optional
        Noise level the Kalman filter assumes (m); default the true ``sigma``. With it fixed, every
        method is affine with data-independent weights and the result is exactly
        :math:`b + g\sigma^2` in the true ``sigma``.
    delay : float
        Unmodelled latency (s): the sample stamped :math:`t_i` was taken at :math:`t_i - \text{delay}`; negative:
        after its stamp. The true sample times must lie in the flight, from its start at t = 0 to the end of the
        record (``SCENARIO["duration"]``, or the last stamp if later), where the truth :math:`x(t)` is the UAV's:
        :math:`t_{\rm last} - \text{end} \le \text{delay} \le t_1` (from -1 s to 1 s for the source's sampling).
    a_after : float, optional
        Acceleration (m/s²) after ``t_change`` (:func:`manoeuvre_truth`); default none (the source's truth).
    t_change : float
        Time of the change (s); 0 with ``a_after=0`` gives a constant-velocity target. Checked also without
        ``a_after``.

    Returns
    -------
    float
        The method's registration MSE (m²) computed in closed form, without simulation.
    """
    t_src, t_dst = (read_once(t_src, "t_src"), read_once(t_dst, "t_dst"))  # converted once (fuzz 29a C5)
    sigma = std_scalar(sigma, "sigma")
    sf = sigma if sigma_filter is None else std_scalar(sigma_filter, "sigma_filter")
    delay = scalar(delay, "delay")
    d1, d2 = instants()
    sigma, q_v, q_a = _check_args(d1 if t_src is None else t_src, d2 if t_dst is None else t_dst, sigma, q_v, q_a)
    t1 = d1 if t_src is None else np.asarray(t_src, dtype=float)
    t2 = d2 if t_dst is None else np.asarray(t_dst, dtype=float)
    _precise_times(t1, t2)
    name = _check_name(name)
    _registration_work([name], t1.size, t2.size, t1.size + 1, "t_src and t_dst")  # rule 17: n1 + 1 registrations
    if delay != 0.0:
        lo, hi = _delay_bounds(t1, t2)
        if not lo <= delay <= hi:
            raise ValueError(f"delay must keep sensor 1's true sample times t_src - delay within the flight (from "
                             f"t = 0, where the truth is the UAV's): {lo:g} <= delay <= {hi:g} s, got {shown(delay)}")
    return reg.expected_mse(registrar(name, t1, t2, sf, q_v, q_a, kf=kf, window=window),
                            manoeuvre_truth(t1 - delay, a_after, t_change), manoeuvre_truth(t2, a_after, t_change), sigma)


@_times_named
def noise_free_mse(name: str, t_src: ArrayLike | None = None, t_dst: ArrayLike | None = None,
                   sigma: float = 1.0, q_v: float = Q_V, q_a: float = Q_A) -> float:
    """Registration MSE (m²) of one method on the noise-free samples (the squared bias term of eq. reg-mse).

    Parameters
    ----------
    name : str
        A key of :data:`METHODS`.
    t_src, t_dst : array_like, optional
        Sample times and instants (s); default :func:`instants`. Refused, named, so far from the flight's start
        (t = 0) that the true positions lose the precision of the errors (``_precise_times``: about 6e4 s). Their
        sizes are held to the work budget, refused by name before any work (``_registration_work``).
    sigma : float
        Noise standard deviation the Kalman methods assume (m); unused by the others.
    q_v, q_a : float
        Kalman tuning.

    Returns
    -------
    float
        :math:`\\frac1K\\sum_k b_k^2`, the MSE of Shi, Suo & Ma's (2023) simulations 1-2, which
        assume no observation error.
    """
    name = _check_name(name)
    d1, d2 = instants()
    t1 = d1 if t_src is None else as_times(t_src, "t_src")
    t2 = d2 if t_dst is None else as_times(t_dst, "t_dst")
    sigma, q_v, q_a = _check_args(t1, t2, sigma, q_v, q_a)
    _precise_times(t1, t2)
    _registration_work([name], t1.size, t2.size, 1, "t_src and t_dst", period_change=False)  # rule 17, named here
    est = register(name, t1, truth(t1), t2, sigma, q_v, q_a)
    return float(np.mean((est - truth(t2)) ** 2))


def noise_gain(name: str) -> float:
    r"""Noise amplification :math:`g = \frac1K\sum_k\lVert a_k\rVert^2` of a fixed-weight method.

    For a method whose weights do not depend on the noise (interpolation, extrapolation, least
    squares), :math:`E[\mathrm{MSE}](\sigma) = b + g\sigma^2` with :math:`b` the noise-free MSE
    (:func:`noise_free_mse`): the growth of the expected MSE per unit of :math:`\sigma^2`.

    Parameters
    ----------
    name : str
        A key of :data:`METHODS` that is not a Kalman method.

    Returns
    -------
    float
        :math:`g` (dimensionless: m² of MSE per m² of noise variance).

    Raises
    ------
    ValueError
        A Kalman method (its gains depend on the noise level).
    """
    name = _fixed_weight_name(name, "name")
    return expected(name, 1.0) - noise_free_mse(name)


def _fixed_weight_name(name: str, arg: str) -> str:
    """A key of :data:`METHODS` that is not a Kalman method, refused under ``arg``, the caller's argument (fuzz 53b C3:
    ``crossing_sigma`` refused a Kalman ``b`` through ``noise_gain``, naming its ``name``)."""
    name = _check_name(name, arg)
    if name in _KALMAN:
        raise ValueError(f"{arg} must be a fixed-weight method, got the Kalman method {shown(name)}")
    return name


def crossing_sigma(a: str, b: str) -> float:
    r"""Noise level (m) at which fixed-weight methods ``a`` and ``b`` have equal expected MSE.

    Solves :math:`b_a + g_a\sigma^2 = b_b + g_b\sigma^2` (:func:`noise_free_mse`,
    :func:`noise_gain`).

    Parameters
    ----------
    a, b : str
        Keys of :data:`METHODS`, not Kalman methods.

    Returns
    -------
    float
        The crossing :math:`\sigma` (m); ``nan`` when the curves never cross at a positive level.

    Raises
    ------
    ValueError
        ``a`` or ``b`` not a key of :data:`METHODS`, or a Kalman method (named by its argument).
    """
    a, b = _fixed_weight_name(a, "a"), _fixed_weight_name(b, "b")
    db = noise_free_mse(b) - noise_free_mse(a)
    dg = noise_gain(a) - noise_gain(b)
    if dg == 0 or db / dg <= 0:
        return float("nan")
    return float(np.sqrt(db / dg))


def two_point_remainder(t_src: ArrayLike, t_dst: ArrayLike) -> FloatArray:
    r"""Derived noise-free error of two-point interpolation on the scenario's trajectory (m).

    The interpolation remainder of a quadratic with second derivative :math:`a`:
    :math:`\hat z(t) - x(t) = \tfrac a2 (t - t_i)(t_{i+1} - t)` for :math:`t_i \le t < t_{i+1}`.

    Parameters
    ----------
    t_src : array_like, shape (n,)
    t_dst : array_like, shape (K,), inside ``[t_src[0], t_src[-1])``

    Returns
    -------
    ndarray, shape (K,)
        At each ``t_dst``: a/2 · (t − tᵢ)(tᵢ₊₁ − t), the error of linear interpolation between the bracketing samples.
    """
    t_src, t_dst = (read_once(t_src, "t_src"), read_once(t_dst, "t_dst"))  # converted once (fuzz 29a C5)
    as_times(t_src, "t_src")
    as_times(t_dst, "t_dst")
    ts = np.asarray(t_src, dtype=float)
    td = np.asarray(t_dst, dtype=float)
    if np.any(td < ts[0]) or np.any(td >= ts[-1]):
        raise ValueError("t_dst must lie inside [t_src[0], t_src[-1]) (interpolation only)")
    i = np.searchsorted(ts, td, side="right") - 1
    return 0.5 * SCENARIO["a"] * (td - ts[i]) * (ts[i + 1] - td)


@dataclass(frozen=True)
class MonteCarlo:
    """Per-run registration MSE of several methods on the same noisy runs.

    Attributes
    ----------
    per_run : mapping of RegMethod to ndarray, shape (runs,)
        :math:`\\frac1K\\sum_k(\\hat x(t_k) - x(t_k))^2` (m²) of each method in each run.
    sigma : float
        Noise standard deviation (m).
    runs : int
    seed : int
    """

    per_run: Mapping[RegMethod, FloatArray]
    sigma: float
    runs: int
    seed: int

    __result_spec__ = ResultSpec({"per_run": dict_of(array("runs", bounds=NONNEGATIVE)), "sigma": number(positive=True),
                                  "runs": integer(2, dim="runs"), "seed": integer(0)})
    __post_init__ = validated_post_init


def _weights(name: str, t_src: FloatArray, t_dst: FloatArray, window: float | None) -> FloatArray:
    """Weight matrix W (K, n) of a fixed-weight method: the method run on each unit vector (column j = method(e_j)).

    Every non-Kalman method of :data:`METHODS` is linear in the samples (interpolation, extrapolation, least
    squares, splines), so registering a run ``z`` is ``W @ z`` exactly; ``tests/test_registration.py`` checks
    it against running the method on each run.
    """
    eye = np.eye(t_src.size)
    return np.column_stack([register(name, t_src, eye[j], t_dst, 1.0, window=window) for j in range(t_src.size)])


def _registered_runs(name: str, t_src: FloatArray, xs: FloatArray, t_dst: FloatArray) -> FloatArray:
    """Registered values (runs, K) of a Kalman method from its states (runs, n, 3)."""
    base = _ON_STATES[name]
    if base is None:
        i = np.clip(np.searchsorted(t_src, t_dst, side="right") - 1, 0, t_src.size - 1)
        dt = t_dst - t_src[i]
        return xs[:, i, 0] + dt * xs[:, i, 1] + 0.5 * dt**2 * xs[:, i, 2]
    return xs[:, :, 0] @ _weights(base, t_src, t_dst, None).T


@derived_inputs()
def monte_carlo(names: Sequence[str], sigma: float, runs: int, seed: int, *,
                t_src: ArrayLike | None = None, t_dst: ArrayLike | None = None,
                q_v: float = Q_V, q_a: float = Q_A, kf: Mapping[str, Any] | None = None,
                window: float | None = None, sigma_filter: float | None = None,
                delay: float = 0.0, a_after: float | None = None, t_change: float = 20.0) -> MonteCarlo:
    """Run every named method on the same ``runs`` noisy sample vectors and score each run.

    Each run draws ``z = x(t_src - delay) + sigma * N(0, 1)`` once
    (``numpy.random.default_rng(seed)``) and every method registers that ``z``; the Kalman filter
    is run once for all runs (vectorised, :func:`fusion.registration.methods.kalman_runs`) and
    shared by the methods built on it. The fixed-weight methods are linear in the samples: each is
    run once on every unit vector and its weight matrix applied to all runs (the same numbers as
    running it on each run, to rounding). Per-run MSEs are rounded to 1e-10 m².

    Parameters
    ----------
    names : sequence of str
        Keys of :data:`METHODS`. Each entry weighs at least ``MC_NAME_UNITS`` units of work (its check, call and MSE:
        22-25 us measured for a Kalman method; about 333,000 names in all), refused by their number before any entry
        is read.
    sigma : float
        Measurement-noise standard deviation (m), > 0.
    runs : int
        Number of runs, >= 2.
    seed : int
    t_src, t_dst : array_like, optional
        Sample times and instants (s); default :func:`instants`. Refused, named, so far from the flight's start
        (t = 0) that the true positions lose the precision of the errors (``_precise_times``: about 6e4 s). Their
        sizes are held to the work budget, refused by name before any work (``_registration_work``).
    q_v, q_a : float
        Kalman tuning.
    kf : mapping, optional
        Further filter options (:data:`KF_OPTIONS`).
    window : float, optional
        Least-squares window (s). Checked, as ``kf`` is, whatever the method, also one that does not use it.
    sigma_filter : float, optional
        Noise level the filter assumes (m); default ``sigma``.
    delay : float
        Unmodelled latency of sensor 1's time stamps (s).
    a_after : float, optional
        Acceleration (m/s²) after ``t_change`` (:func:`manoeuvre_truth`); default none (the source's truth).
    t_change : float
        Time of the change (s); 0 with ``a_after=0`` gives a constant-velocity target. Checked also without
        ``a_after``.

    Returns
    -------
    MonteCarlo
        ``per_run``: method name → its per-run registration MSE (m², shape (runs,)), with ``sigma``, ``runs`` and
        ``seed``. ``runs`` x (samples + instants) x methods, and the weight matrices (a registration per sample by
        each method, ``_registration_work``), are held to the work budget (``fusion._limits.MAX_WORK``, refused by
        name before any draw: a ``t_dst`` of 2,000 instants with the four least-squares methods, ~2 s, is refused).
    """
    t_src, t_dst = (read_once(t_src, "t_src"), read_once(t_dst, "t_dst"))  # converted once (fuzz 29a C5)
    if isinstance(names, (str, bytes)):
        raise TypeError(f"names must be a sequence of method names, got the string {shown(names)}")
    items = sequence(names, "names")   # the list read once, used after (fuzz 61a C4's class)
    sigma = std_scalar(sigma, "sigma")
    sf = sigma if sigma_filter is None else std_scalar(sigma_filter, "sigma_filter")
    delay = scalar(delay, "delay")
    runs = count(runs, "runs", minimum=2)
    seed = check_seed(seed)
    d1, d2 = instants()
    sigma, q_v, q_a = _check_args(d1 if t_src is None else t_src, d2 if t_dst is None else t_dst, sigma, q_v, q_a)
    t1 = d1 if t_src is None else np.asarray(t_src, dtype=float)
    t2 = d2 if t_dst is None else np.asarray(t_dst, dtype=float)
    _precise_times(t1, t2)
    # rule 17 by len(names) before any entry is read (fuzz 62b C1: 10**7 names were each checked first, refused after
    # 7.1-9.3 CPU-s): every entry weighs at least MC_NAME_UNITS, counted again with the rest below
    work((len(items),), "names, t_src and t_dst", weight=MC_NAME_UNITS)
    unknown = [n for n in items if not isinstance(n, str) or n not in METHODS]
    if unknown:
        raise ValueError(f"names must be keys of METHODS {sorted(METHODS)}; unknown: {shown(unknown)}")
    names = [_check_name(n, f"names[{i}]") for i, n in enumerate(items)]  # plain texts, entries named (fuzz 32a C4)
    _monte_carlo_work(names, runs, t1.size, t2.size, "runs, names, t_src and t_dst", "names, t_src and t_dst",
                      name_units=MC_NAME_UNITS)
    kf, window = _options(kf, window, t2)
    rng = np.random.default_rng(seed)
    z = manoeuvre_truth(t1 - delay, a_after, t_change) + sigma * rng.standard_normal((int(runs), t1.size))
    x2 = manoeuvre_truth(t2, a_after, t_change)
    states = _filtered(names, t1, z, t2, sf, q_v, q_a, kf)
    out = {}
    for n in names:
        if n in _KALMAN:
            est = _registered_runs(n, t1, states[_STATES.get(n, "filtered")], t2)  # type: ignore[arg-type]
        else:
            est = z @ _weights(n, t1, t2, window).T
        out[RegMethod(n)] = np.mean((est - x2) ** 2, axis=1)
    return MonteCarlo(per_run={n: np.round(v, 10) for n, v in out.items()}, sigma=float(sigma), runs=int(runs),
                      seed=int(seed))


@_times_named
def mse_coefficients(name: str, sigma_filter: float = 1.0, t_src: ArrayLike | None = None,
                     t_dst: ArrayLike | None = None, q_v: float = Q_V, q_a: float = Q_A, *,
                     kf: Mapping[str, Any] | None = None) -> tuple[float, float]:
    r"""Coefficients of the closed form :math:`E[\mathrm{MSE}](\sigma) = b + g\sigma^2` of one method.

    With fixed weights (the Kalman methods with their assumed noise level fixed at
    ``sigma_filter``) the registered values are :math:`f_0 + A\mathbf v`, so
    :math:`b = \frac1K\sum_k (f_{0,k} - x(t_k))^2` and
    :math:`g = \frac1K\sum_k\lVert a_k\rVert^2 = \frac1K\,\mathrm{tr}(AA^\top)`.

    Parameters
    ----------
    name : str
        A key of :data:`METHODS`.
    sigma_filter : float
        Noise level the Kalman methods assume (m), > 0; unused by the others.
    t_src, t_dst : array_like, optional
        Sample times and instants (s); default :func:`instants`. Refused, named, so far from the flight's start
        (t = 0) that the true positions lose the precision of the errors (``_precise_times``: about 6e4 s). Their
        sizes are held to the work budget, refused by name before any work (``_registration_work``).
    q_v, q_a : float
        Kalman tuning.
    kf : mapping, optional
        Further filter options (:data:`KF_OPTIONS`).

    Returns
    -------
    tuple of float
        ``(b, g)``: squared bias (m²) and noise gain (dimensionless).
    """
    name = _check_name(name)
    sf = std_scalar(sigma_filter, "sigma_filter")
    d1, d2 = instants()
    t1 = d1 if t_src is None else as_times(t_src, "t_src")
    t2 = d2 if t_dst is None else as_times(t_dst, "t_dst")
    sf, q_v, q_a = _check_args(t1, t2, sf, q_v, q_a)
    _precise_times(t1, t2)
    _registration_work([name], t1.size, t2.size, t1.size + 1, "t_src and t_dst")  # rule 17: n1 + 1 registrations
    dec = reg.affine_decomposition(registrar(name, t1, t2, sf, q_v, q_a, kf=kf), truth(t1))
    return float(np.mean((dec.f0 - truth(t2)) ** 2)), float(np.mean(np.sum(dec.A**2, axis=1)))


@dataclass(frozen=True)
class FusionRuns:
    """Per-run MSE (m²) of sensor 2 alone and of its fusion with sensor 1 registered several ways.

    Attributes
    ----------
    alone : ndarray, shape (runs,)
        Sensor 2 alone.
    unregistered : ndarray, shape (runs,)
        Fused with sensor 1's last sample not later than the instant, taken as simultaneous.
    fused : dict of RegMethod to ndarray, shape (runs,)
        Fused with sensor 1 registered by each method.
    sigma : float
    runs : int
    seed : int
    """

    alone: FloatArray
    unregistered: FloatArray
    fused: Mapping[RegMethod, FloatArray]
    sigma: float
    runs: int
    seed: int

    __result_spec__ = ResultSpec({"alone": array("runs", bounds=NONNEGATIVE),
                                  "unregistered": array("runs", bounds=NONNEGATIVE),
                                  "fused": dict_of(array("runs", bounds=NONNEGATIVE)), "sigma": number(positive=True),
                                  "runs": integer(2, dim="runs"), "seed": integer(0)})
    __post_init__ = validated_post_init


@derived_inputs()
def fusion_runs(names: Sequence[str], sigma: float, runs: int, seed: int) -> FusionRuns:
    r"""The fusion step the source says registration improves, run on noisy data.

    Sensor 2 measures :math:`z^{(2)}_k = x(t_k) + \sigma\varepsilon_k`; sensor 1's samples are
    registered onto :math:`t_k` (or, *unregistered*, its last sample not later than :math:`t_k`
    is taken as simultaneous) and fused with :math:`z^{(2)}_k` by inverse-variance weights.
    Information used: each registered value's noise variance :math:`\sigma^2\lVert a_k\rVert^2`
    from the method's own weights (no truth); the unregistered sample's nominal :math:`\sigma^2`.
    Sensor 1's noise is drawn as in :func:`monte_carlo` with the same seed; sensor 2's from the
    next stream of the same generator.

    Parameters
    ----------
    names : sequence of str
        Registration methods (keys of :data:`METHODS`).
    sigma : float
        Noise standard deviation of both sensors (m), > 0.
    runs : int
        Number of runs, >= 2. ``runs`` x the methods of ``names`` (each run registered by a Python call, 30 to
        300 us measured) are held to the work budget (``fusion._limits.MAX_WORK``, about 10 CPU-s), refused by name
        before any draw (``_fusion_runs_work``, a Kalman method's filter pass also by the filter's own rule):
        188,667 runs of one Kalman method, 100,000 of a fixed-weight method and 33,333 of a method fitting each
        instant or of the cubic spline are accepted, one more refused.
    seed : int

    Returns
    -------
    FusionRuns
        Per-run MSE (m²) of sensor 2 alone, fused unregistered, and fused after each method's registration.

    Raises
    ------
    ValueError
        An unknown method, a ``sigma`` or ``runs`` out of range; ``runs`` with ``names`` beyond the work budget,
        named ``runs and names``.
    """
    if isinstance(names, (str, bytes)):
        raise TypeError(f"names must be a sequence of method names, got the string {shown(names)}")
    items = sequence(names, "names")   # the list read once, used after (fuzz 61a C4's class)
    sigma = std_scalar(sigma, "sigma")
    runs = count(runs, "runs", minimum=2)
    seed = check_seed(seed)
    t1, t2 = instants()
    # rule 17 by len(names) before any entry is read (fuzz 62b C1: 10**7 names were each checked first, refused after
    # 5.2 CPU-s): each method's weight matrix is at least n_src + 1 registrations of 10 * LOOP_STEP
    # (``_registration_work``, counted again below by method)
    work((t1.size + 1, len(items)), "names", weight=10 * LOOP_STEP)
    names = [_check_name(n, f"names[{i}]") for i, n in enumerate(items)]  # plain texts, entries named (fuzz 32a C4)
    _fusion_runs_work(names, runs, t1.size, t2.size, "runs and names", "names")  # rule 17 (fuzz 39a C4)
    rng = np.random.default_rng(seed)
    z1 = truth(t1) + sigma * rng.standard_normal((runs, t1.size))
    z2 = truth(t2) + sigma * rng.standard_normal((runs, t2.size))
    x2 = truth(t2)
    alone = np.mean((z2 - x2) ** 2, axis=1)
    last = np.clip(np.searchsorted(t1, t2, side="right") - 1, 0, None)
    unregistered = np.mean(((z1[:, last] + z2) / 2 - x2) ** 2, axis=1)
    out = {}
    states = _filtered(names, t1, z1, t2, sigma, Q_V, Q_A, None)
    for n in names:
        var = sigma**2 * np.sum(reg.affine_decomposition(registrar(n, t1, t2, sigma), truth(t1)).A ** 2, axis=1)
        w = sigma**2 / (sigma**2 + var)            # weight of the registered value
        est = np.empty((runs, t2.size))
        for r in range(runs):
            if n in _KALMAN:
                est[r] = _from_filtered(n, t1, states[_STATES.get(n, "filtered")][r], t2)  # type: ignore[index]
            else:
                est[r] = register(n, t1, z1[r], t2, sigma)
        out[RegMethod(n)] = np.mean((w * est + (1 - w) * z2 - x2) ** 2, axis=1)
    return FusionRuns(alone=np.round(alone, 10), unregistered=np.round(unregistered, 10),
                      fused={k: np.round(v, 10) for k, v in out.items()}, sigma=float(sigma), runs=int(runs),
                      seed=int(seed))
