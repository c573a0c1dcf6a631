r"""Infrared + radar case of Wang & Tang (2024, §3.5 item 3, Figs. 9-10), vectorised over Monte-Carlo runs.

An infrared sensor (红外) measures azimuth and elevation; a radar (雷达) measures range,
azimuth and elevation. Both sit at the origin (the source does not place them; co-located is
the usual set-up for this pairing). Each sensor tracks its angles with a linear
constant-velocity Kalman filter in angle space, state :math:`[\alpha, \dot\alpha, \varepsilon,
\dot\varepsilon]` (rad, rad/s), the radar also tracks range with state :math:`[r, \dot r]`
(m, m/s). The fusion centre fuses the two *angle* tracks (the only quantities both sensors
observe) with any rule of :func:`fusion.filtering.tracks.fuse_tracks`, and converts the fused angles
with the radar's range to Cartesian position:

.. math:: x = r\cos\varepsilon\cos\alpha, \quad y = r\cos\varepsilon\sin\alpha, \quad
          z = r\sin\varepsilon .

The target flies a straight line at constant velocity, so its angles and range are smooth but
not constant-velocity in angle space; each filter's white-acceleration process noise is set to
the largest second derivative of the true coordinate (the rule of thumb
:math:`\sigma_a \approx a_{\max}`, Bar-Shalom, Li & Kirubarajan 2001, §6.2). That model
mismatch is common to both sensors and is the correlated part of their errors.
"""

from __future__ import annotations

import hashlib
import math

from collections.abc import Mapping, Sequence
from dataclasses import dataclass
from enum import StrEnum

import numpy as np
from filterpy.common import Q_discrete_white_noise
from numpy.typing import ArrayLike

from fusion._frozen import constant
from fusion._results import ResultSpec, array, nested, number, numbers, trusted, validated_post_init
from fusion._validation import given_entries, read_mapping, read_once
from fusion._limits import MAX_INPUT_ELEMENTS
from fusion._validation import derived_inputs
from fusion._validation import (FloatArray, as_array, as_rng, count, instance_of, nonnegative_scalar, one_of,
                                grid_points, positive_scalar, scalar, std_scalar, step_scalar, work)
from fusion._counts import allocation, broadcast, distinct, sequence
from fusion._validation import LOOP_STEP
from fusion._validation import flag, text
from fusion._options import text_key
from fusion.filtering.tracks import LocalTrack, _named_track, _symmetric_parts, fuse_tracks
from fusion.scenarios._infrared_budget import (_reader_budget, _scan_budget, _semidefinite_tracks, _simulate_budget,
                                               _tracks_budget)
from fusion.filtering.kalman import cv_model
from fusion._shown import shown

__all__ = [
    "Truth",
    "spherical_to_cartesian",
    "cartesian_to_spherical",
    "truth",
    "white_acceleration",
    "IrRadarRuns",
    "simulate",
    "position",
    "IrMethod",
    "RULES",
    "PER_SCAN",
    "rule_errors",
    "rmse_by_rule",
    "late_means",
    "BOUND_SENSORS",
    "many_scan_bound",
    "conversion_jacobian",
    "CartesianTracks",
    "cartesian_tracks",
    "CARTESIAN_LOCAL",
    "cartesian_errors",
]


#: Keys of :func:`late_means`' per-method entries, which chapter 05's tables and claim evidence read by these names
#: (issue 36: a header named once): the late mean RMSE of the azimuth and the elevation (mrad) and of x and y (m).
AZIMUTH_MRAD = "azimuth (mrad)"
#: See :data:`AZIMUTH_MRAD`.
ELEVATION_MRAD = "elevation (mrad)"
#: See :data:`AZIMUTH_MRAD`.
X_M = "x (m)"
#: See :data:`AZIMUTH_MRAD`.
Y_M = "y (m)"


def spherical_to_cartesian(r: ArrayLike, az: ArrayLike, el: ArrayLike) -> FloatArray:
    r"""Cartesian position (m), shape (..., 3), from range (m), azimuth and elevation (rad).

    .. math:: (x, y, z) = (r\cos\epsilon\cos\alpha,\; r\cos\epsilon\sin\alpha,\; r\sin\epsilon)

    with azimuth :math:`\alpha` and elevation :math:`\epsilon`.

    Parameters
    ----------
    r : array_like
        Range in m.
    az, el : array_like
        Azimuth and elevation in rad, broadcast with ``r``.

    Returns
    -------
    ndarray, shape (..., 3)
        Position in m.

    Raises
    ------
    ValueError
        Non-finite inputs, a negative range ``r`` (a coordinate; the track readers, :func:`position`, take a filter's
        negative range estimate as it is), or shapes that do not broadcast.
    """
    r, az, el = (as_array(v, n, nonempty=False) for v, n in ((r, "r"), (az, "az"), (el, "el")))
    if np.any(r < 0):
        raise ValueError("r (range) must be non-negative")
    # rules 9 and 17 on the broadcast (fuzz 57b C5): 7.0 arrays of it at tracemalloc's peak, 37 ns an element
    broadcast((("r", r.shape), ("az", az.shape), ("el", el.shape)), arrays=7, weight=4)
    return _cartesian(*np.broadcast_arrays(r, az, el))  # the three coordinates stacked share one shape


def _cartesian(r: FloatArray, az: FloatArray, el: FloatArray) -> FloatArray:
    """:func:`spherical_to_cartesian`'s formula on checked arrays of one shape, any sign of ``r``: a filter's range
    estimate or a noisy range measurement below 0 is a valid reading (its point lies through the origin, its error
    large; fuzz 42a C8: the readers refused a valid simulation at sigma_range = 1,000 m naming ``r``)."""
    c = r * np.cos(el)
    return np.stack([c * np.cos(az), c * np.sin(az), r * np.sin(el)], axis=-1)


def cartesian_to_spherical(p: ArrayLike) -> FloatArray:
    r"""Range (m), azimuth, elevation (rad), shape (..., 3), from Cartesian position (..., 3).

    The inverse of :func:`spherical_to_cartesian`: :math:`r = \lVert p\rVert`,
    :math:`\alpha = \operatorname{atan2}(y, x)`, :math:`\epsilon = \arcsin(z/r)`.

    Parameters
    ----------
    p : array_like, shape (..., 3)
        Position in m.

    Returns
    -------
    ndarray, shape (..., 3)
        Range (m), azimuth (rad), elevation (rad).

    Raises
    ------
    ValueError
        Wrong shape, non-finite positions, or a position at the sensor (range 0).
    """
    p = as_array(p, "p")
    if p.ndim < 1 or p.shape[-1] != 3:
        raise ValueError(f"p (positions) must have shape (..., 3), got {p.shape}")
    r = np.linalg.norm(p, axis=-1)
    if np.any(r == 0):
        raise ValueError("p has a point at the sensor: its angles are undefined (range 0)")
    return np.stack([r, np.arctan2(p[..., 1], p[..., 0]), np.arcsin(p[..., 2] / r)], axis=-1)


@dataclass(frozen=True)
class Truth:
    """True trajectory: times, Cartesian and spherical positions.

    Arrays are read-only. Built with ``dataclasses.replace`` or directly, every field is checked
    (``fusion._results``): finite, ``t`` strictly increasing, one position per time, ``sph`` the
    spherical coordinates of ``pos`` (:func:`cartesian_to_spherical`); otherwise a :class:`ValueError`
    naming the field (``Truth.pos: ...``).

    Attributes
    ----------
    t : ndarray, shape (K,)
        Times (s).
    pos : ndarray, shape (K, 3)
        Position (m).
    sph : ndarray, shape (K, 3)
        Range (m), azimuth, elevation (rad).
    """

    t: FloatArray
    pos: FloatArray
    sph: FloatArray

    __result_spec__ = ResultSpec({"t": array("K", increasing=True), "pos": array("K", 3), "sph": array("K", 3)},
                                 relations=(lambda v, cls: _same_geometry(v["pos"], v["sph"], cls),))
    __post_init__ = validated_post_init


#: Tolerance of :func:`_same_geometry`: relative on range, absolute (rad) on the angles (rounding, float32 included).
_GEOMETRY_TOL = 1e-6


def _same_geometry(pos: FloatArray, sph: FloatArray, cls: str) -> None:
    """``sph`` holds the range, azimuth and elevation of ``pos`` (angles modulo 2 pi), to :data:`_GEOMETRY_TOL`."""
    r = np.linalg.norm(pos, axis=-1)
    if np.any(r == 0):
        raise ValueError(f"{cls}.pos has a point at the sensor (range 0): its angles are undefined")
    want = cartesian_to_spherical(pos)
    d_ang = np.angle(np.exp(1j * (sph[:, 1:] - want[:, 1:])))
    if not (np.all(np.abs(sph[:, 0] - want[:, 0]) <= _GEOMETRY_TOL * np.maximum(r, 1.0))
            and np.all(np.abs(d_ang) <= _GEOMETRY_TOL)):
        raise ValueError(f"{cls}.sph must hold the range, azimuth and elevation of {cls}.pos at every time")


def _even_times(t: FloatArray, cls: str) -> None:
    """At least three times, evenly spaced (the filters' period is ``t[1] - t[0]``)."""
    if t.size < 3:
        raise ValueError(f"{cls}.t must hold at least three times, got {t.size}")
    d = np.diff(t)
    if np.any(np.abs(d - d[0]) > _GEOMETRY_TOL * max(float(np.abs(t).max()), float(d[0]))):
        raise ValueError(f"{cls}.t must be evenly spaced (the filters' period is t[1] - t[0])")


@derived_inputs()
def truth(
    T: float = 0.1,
    duration: float = 10.0,
    r0: float = 1000.0,
    az0: float = np.pi / 5,
    el0: float = np.pi / 8,
    velocity: tuple[float, float, float] = (300.0, 100.0, 0.0),
) -> Truth:
    """Straight constant-velocity flight from range ``r0`` at azimuth ``az0``, elevation ``el0``.

    The geometry is our choice: Wang & Tang (2024), §3.5, give none.

    Parameters
    ----------
    T : float
        Sampling period (s), > 0.
    duration : float
        Length of the flight (s), > 0; times ``0, T, ..., duration``.
    r0 : float
        Initial range (m), > 0.
    az0, el0 : float
        Initial azimuth and elevation (rad).
    velocity : (float, float, float)
        Constant Cartesian velocity (m/s).

    Returns
    -------
    Truth
        ``t``, ``pos`` and ``sph``.

    Raises
    ------
    ValueError
        ``T``, ``duration`` or ``r0`` not positive, ``velocity`` not three finite numbers.
    """
    T = positive_scalar(T, "T")
    duration = positive_scalar(duration, "duration")
    grid_points(duration, T, "duration and T")  # rule 9: refused by name before np.arange
    t = np.arange(0.0, duration + 1e-9, T)
    v = as_array(velocity, "velocity", shape=(3,))  # the shared reader: no bool, text or complex entry (fuzz 24a U)
    p0 = spherical_to_cartesian(positive_scalar(r0, "r0"), scalar(az0, "az0"), scalar(el0, "el0"))
    pos = p0 + t[:, None] * v
    return trusted(Truth, t=t, pos=pos, sph=cartesian_to_spherical(pos))  # computed here: the private constructor


def white_acceleration(T: float, sigma: float) -> FloatArray:
    r"""Discrete white-noise-acceleration covariance of one :math:`[p, \dot p]` pair.

    :math:`\sigma^2\begin{bmatrix}T^4/4 & T^3/2\\ T^3/2 & T^2\end{bmatrix}` (``sigma`` in units/s²;
    Bar-Shalom, Li & Kirubarajan 2001).

    Parameters
    ----------
    T : float
        Sampling period (s), > 0 and at most ``1e150 ** (1/4)`` (its 4th power stays representable).
    sigma : float
        Standard deviation of the piecewise-constant acceleration, >= 0: ``sigma = 0`` (no
        acceleration, e.g. a stationary target) gives the zero matrix, a valid positive-semidefinite
        process noise.

    Returns
    -------
    ndarray, shape (2, 2)
        σ² [[T⁴/4, T³/2], [T³/2, T²]], filterpy's ``Q_discrete_white_noise``.

    Raises
    ------
    ValueError
        ``T`` not positive or ``sigma`` negative.
    """
    T = step_scalar(T, "T", 4)
    sigma = nonnegative_scalar(sigma, "sigma")
    return Q_discrete_white_noise(dim=2, dt=T, var=sigma**2)  # filterpy: the same matrix


def _block(a: FloatArray, b: FloatArray) -> FloatArray:
    out = np.zeros((4, 4))
    out[:2, :2], out[2:, 2:] = a, b
    return out


def _max_acceleration(v: FloatArray, T: float) -> float:
    return float(np.max(np.abs(np.diff(v, 2)))) / T**2


@dataclass(frozen=True)
class IrRadarRuns:
    """Simulated infrared + radar runs.

    Arrays are read-only. Built with ``dataclasses.replace`` or directly, every field is checked
    (``fusion._results``): finite, ``t`` at least three evenly spaced times, ``sph`` the spherical
    coordinates of ``pos``, the three tracks of the same runs and steps as ``t`` (angle tracks of
    state 4 and 2 readings, the range track of state 2 and 1 reading), noise levels positive;
    otherwise a :class:`ValueError` naming the field (``IrRadarRuns.sph: ...``).

    Attributes
    ----------
    t : ndarray, shape (K,)
    pos, sph : ndarray, shape (K, 3)
        True position (m) and range/azimuth/elevation (m, rad).
    ir, radar : LocalTrack
        Angle tracks, state [az, az rate, el, el rate].
    radar_range : LocalTrack
        The radar's range track, state [r, r rate].
    sigma_acc : mapping
        Process-noise levels used (rad/s² for the angles, m/s² for range).
    sigma : mapping
        Measurement noise: ``"ir"`` and ``"angle"`` (rad), ``"range"`` (m).
    """

    t: FloatArray
    pos: FloatArray
    sph: FloatArray
    ir: LocalTrack
    radar: LocalTrack
    radar_range: LocalTrack
    sigma_acc: Mapping[str, float]
    sigma: Mapping[str, float]

    __result_spec__ = ResultSpec(
        {"t": array("K", increasing=True), "pos": array("K", 3), "sph": array("K", 3),
         "ir": nested(LocalTrack, runs="runs", K="K", n=4, m=2), "radar": nested(LocalTrack, runs="runs", K="K", n=4, m=2),
         "radar_range": nested(LocalTrack, runs="runs", K="K", n=2, m=1),
         "sigma_acc": numbers("az", "el", "range"), "sigma": numbers("ir", "angle", "range", positive=True)},
        relations=(lambda v, cls: _even_times(v["t"], cls), lambda v, cls: _same_geometry(v["pos"], v["sph"], cls)))
    __post_init__ = validated_post_init

    @property
    def path(self) -> Truth:
        """The true flight as a :class:`Truth` (for :func:`many_scan_bound`)."""
        return trusted(Truth, t=self.t, pos=self.pos, sph=self.sph)  # checked when this object was built


@derived_inputs()
def simulate(
    rng: np.random.Generator,
    runs: int = 50,
    T: float = 0.1,
    duration: float = 10.0,
    sigma_ir: float = 1e-4,
    sigma_angle: float = 0.02,
    sigma_range: float = 5.0,
    rate_sigma: float = 0.5,
    range_rate_sigma: float = 400.0,
    q_scale: float = 1.0,
    **geometry: float,
) -> IrRadarRuns:
    """Measure the target of :func:`truth` with both sensors and run their filters, all runs at once.

    Parameters
    ----------
    rng : numpy.random.Generator
        Draws the infrared noise, then the radar's angle noise, then its range noise.
    runs : int
        Number of Monte-Carlo runs, >= 1.
    T, duration : float
        Sampling period and length of the track (s); both are our choice (the source gives none).
    sigma_ir, sigma_angle, sigma_range : float
        Infrared angle noise (rad), radar angle noise (rad), radar range noise (m).
    rate_sigma, range_rate_sigma : float
        Prior standard deviation of the angle rates (rad/s) and of the range rate (m/s); the
        filters start at the first measurement with zero rates. The rate uncertainty is common
        to both sensors (the same unknown motion).
    q_scale : float
        Factor (> 0) on the variance of every filter's process noise: 1 is the rule of thumb
        :math:`\\sigma_a = a_{\\max}`; other values are the "scaled Q" readings.
    **geometry
        Passed to :func:`truth` (``r0``, ``az0``, ``el0``, ``velocity``).

    Returns
    -------
    IrRadarRuns
        Truth and the three local tracks of every run.

    Raises
    ------
    ValueError
        ``runs`` not positive, fewer than three samples, a noise level not positive, bad geometry (see :func:`truth`),
        ``rate_sigma`` or ``range_rate_sigma`` so large that a track's covariances are not accurate (``local_track``).
    """
    as_rng(rng)
    runs = count(runs, "runs")
    rate_sigma = std_scalar(rate_sigma, "rate_sigma")
    range_rate_sigma = std_scalar(range_rate_sigma, "range_rate_sigma")
    T = positive_scalar(T, "T")  # the validated float: a Decimal would reach the arithmetic below
    true_path = truth(T, duration, **geometry)
    t, pos, sph = true_path.t, true_path.pos, true_path.sph
    _simulate_budget(runs, t.size)   # rules 17 and 9 before any draw (its filters' steps, their input)
    if t.size < 3:
        raise ValueError("the track needs at least three samples (duration >= 2 T)")
    model = cv_model(T)
    F, H = model.F, model.H
    scale = np.sqrt(positive_scalar(q_scale, "q_scale"))
    acc = {"az": scale * _max_acceleration(sph[:, 1], T), "el": scale * _max_acceleration(sph[:, 2], T),
           "range": scale * _max_acceleration(sph[:, 0], T)}
    Q = _block(white_acceleration(T, acc["az"]), white_acceleration(T, acc["el"]))
    P0d = np.diag([0.0, rate_sigma**2, 0.0, rate_sigma**2])
    angles = sph[None, :, 1:]
    tracks = []
    for s in (std_scalar(sigma_ir, "sigma_ir"), std_scalar(sigma_angle, "sigma_angle")):
        z = angles + s * rng.standard_normal((runs, t.size, 2))
        x0 = np.column_stack([z[:, 0, 0], np.zeros(runs), z[:, 0, 1], np.zeros(runs)])
        tracks.append(_named_track("rate_sigma", z, F, H, Q, np.diag([s**2, s**2]), x0, P0d, np.diag([s**2, 0.0, s**2, 0.0])))
    sr = std_scalar(sigma_range, "sigma_range")
    zr = sph[None, :, :1] + sr * rng.standard_normal((runs, t.size, 1))
    Fr, Hr = F[:2, :2], H[:1, :2]
    rng_track = _named_track("range_rate_sigma", zr, Fr, Hr, white_acceleration(T, acc["range"]), np.array([[sr**2]]),
                            np.column_stack([zr[:, 0, 0], np.zeros(runs)]),
                            np.diag([0.0, range_rate_sigma**2]), np.diag([sr**2, 0.0]))
    return trusted(IrRadarRuns, t=t, pos=pos, sph=sph, ir=tracks[0], radar=tracks[1], radar_range=rng_track,
                   sigma_acc=acc, sigma={"ir": float(sigma_ir), "angle": float(sigma_angle), "range": sr})


def position(range_est: ArrayLike, angle_est: ArrayLike) -> FloatArray:
    """Cartesian position (..., 3) from range tracks (..., 2) and angle tracks (..., 4).

    Uses the range of ``range_est[..., 0]`` and the angles ``angle_est[..., 0]`` (azimuth) and
    ``angle_est[..., 2]`` (elevation) in the formula of :func:`spherical_to_cartesian`. A negative range estimate
    (a filter's output under a large range noise) is used as it is: its position lies through the origin.

    Parameters
    ----------
    range_est : array_like, shape (..., 2)
        Range tracks :math:`[r, \\dot r]` (m, m/s).
    angle_est : array_like, shape (..., 4)
        Angle tracks [az, az rate, el, el rate] (rad, rad/s).

    Returns
    -------
    ndarray, shape (..., 3)
        Position in m.

    Raises
    ------
    ValueError
        Wrong trailing shapes or non-finite tracks.
    """
    r = as_array(range_est, "range_est")
    a = as_array(angle_est, "angle_est")
    if r.ndim < 1 or a.ndim < 1 or r.shape[-1] != 2 or a.shape[-1] != 4 or r.shape[:-1] != a.shape[:-1]:
        raise ValueError(f"need range tracks range_est (..., 2) and angle tracks angle_est (..., 4), "
                         f"got {r.shape} and {a.shape}")
    if not (np.all(np.isfinite(r)) and np.all(np.isfinite(a))):
        raise ValueError("range and angle tracks must be finite")
    return _cartesian(r[..., 0], a[..., 0], a[..., 2])


class IrMethod(StrEnum):
    """Method keys of the infrared + radar results; display labels in :data:`fusion.book.style.METHOD_LABELS`.

    The rules share their keys with :class:`fusion.scenarios.two_sensor.StudyMethod` (the same rule, the same
    label and colour).

    Attributes
    ----------
    IR_ALONE, RADAR_ALONE
        Each sensor's angle-space filter alone.
    CI, SPLIT_CI, CONVEX, FUZZY
        The fusion rules of :data:`RULES`.
    PER_SCAN
        The unfiltered reference: each scan's raw infrared angles with the radar's raw range.
    CARTESIAN_RADAR, CARTESIAN_IR
        The two Cartesian tracks of :func:`cartesian_errors`: the radar alone, and the infrared angles with
        the radar's range.
    """

    IR_ALONE = "ir_alone"
    RADAR_ALONE = "radar_alone"
    CI = "ci_closed_form"
    SPLIT_CI = "split_ci"
    CONVEX = "convex_ml"
    FUZZY = "fuzzy_clustering"
    PER_SCAN = "ir_per_scan"
    CARTESIAN_RADAR = "radar_alone_cartesian"
    CARTESIAN_IR = "ir_radar_cartesian"


#: The fusion rules compared in chapter 05: method key -> rule of :func:`fusion.filtering.tracks.fuse_tracks`.
RULES: dict[IrMethod, str] = constant({
    IrMethod.CI: "ci",
    IrMethod.SPLIT_CI: "split",
    IrMethod.CONVEX: "convex",
    IrMethod.FUZZY: "fuzzy",
})

#: Key of the unfiltered reference in :func:`rule_errors`.
PER_SCAN = IrMethod.PER_SCAN


def _rule_subset(rules: Sequence[str] | None) -> dict[IrMethod, str]:
    if rules is None:
        return dict(RULES)
    if isinstance(rules, str):
        raise ValueError(f"rules must be a sequence of keys of RULES, got the string {shown(rules)}")
    if not isinstance(rules, Sequence):
        raise TypeError(f"rules must be a sequence of keys of RULES, got {type(rules).__name__}")
    if len(rules) > len(RULES):   # by its length, before any entry is read: each rule at most once (repeats refused)
        raise ValueError(f"rules must name each of the {len(RULES)} keys of RULES at most once, got {len(rules):,} "
                         "entries")
    rules = sequence(rules, "rules")   # its items, a ``__len__`` that disagrees with them refused
    if not all(isinstance(r, str) for r in rules):
        raise TypeError(f"rules must hold keys (strings) of RULES, got {shown(list(rules))}")
    unknown = [r for r in rules if r not in RULES]
    if unknown:
        raise ValueError(f"rules must be keys of RULES ({sorted(map(str, RULES))}), got {shown(unknown)}")
    rules = distinct([text(r, f"rules[{i}]") for i, r in enumerate(rules)], "rules")  # plain texts (rule 19), once
    return {IrMethod(name): RULES[IrMethod(name)] for name in rules}


def rule_errors(sim: IrRadarRuns, rules: Sequence[str] | None = None) -> dict[IrMethod, FloatArray]:
    """Errors of each sensor alone, each rule of :data:`RULES`, and the unfiltered reference.

    Every rule fuses the two angle tracks; positions use the radar's range track (:func:`position`: a negative range
    estimate as it is). The reference :data:`PER_SCAN` takes each scan's raw infrared angles with the radar's raw
    range (no filter).

    Parameters
    ----------
    sim : IrRadarRuns
        Output of :func:`simulate`.
    rules : sequence of str, optional
        Keys of :data:`RULES` to run (default: all).

    Returns
    -------
    dict of IrMethod to ndarray, shape (runs, K, 4)
        Errors of azimuth (rad), elevation (rad), x (m), y (m).

    Raises
    ------
    ValueError
        A key in ``rules`` that is not in :data:`RULES` or is named twice (more entries than RULES: by the length);
        ``sim``'s runs times scans beyond the work, memory or input budget of this reading (270 units a run and
        scan with every rule, 13 arrays of 4 entries; about 3.7 million with every rule), refused before any work.
    """
    instance_of(sim, IrRadarRuns, "sim")
    subset = _rule_subset(rules)
    _reader_budget("rule_errors", *sim.ir.est.shape, subset, "sim (its runs and scans) and rules")
    angle_tracks = {IrMethod.IR_ALONE: sim.ir.est, IrMethod.RADAR_ALONE: sim.radar.est}
    for name, rule in subset.items():
        angle_tracks[name] = fuse_tracks(sim.ir, sim.radar, rule).est
    out = {name: _errors(sim, position(sim.radar_range.est, est), est[..., 0::2]) for name, est in angle_tracks.items()}
    raw = _cartesian(sim.radar_range.z[..., 0], sim.ir.z[..., 0], sim.ir.z[..., 1])  # a range below 0: as measured
    out[PER_SCAN] = _errors(sim, raw, sim.ir.z)
    return out


def rmse_by_rule(sim: IrRadarRuns) -> dict[IrMethod, FloatArray]:
    """RMSE over the runs per scan of each entry of :func:`rule_errors`.

    Parameters
    ----------
    sim : IrRadarRuns
        Output of :func:`simulate`.

    Returns
    -------
    dict of IrMethod to ndarray, shape (K, 4)
        Azimuth (rad), elevation (rad), x (m), y (m).

    Raises
    ------
    ValueError
        ``sim`` beyond the budget of :func:`rule_errors`, refused before any work.
    """
    return {name: np.sqrt(np.mean(e**2, axis=0)) for name, e in rule_errors(sim).items()}


def late_means(rmse: dict[str, FloatArray], t: ArrayLike, t_min: float = 2.0) -> dict[str, dict[str, float]]:
    """Time average over ``t >= t_min`` (after the filters' start-up) of each method's RMSE per scan.

    Parameters
    ----------
    rmse : dict of str to ndarray, shape (K, 4)
        From :func:`rmse_by_rule`.
    t : array_like, shape (K,)
        Scan times (s).
    t_min : float
        Start of the average (s).

    Returns
    -------
    dict of str to dict
        Per method: ``"azimuth (mrad)"``, ``"elevation (mrad)"``, ``"x (m)"``, ``"y (m)"``.

    Raises
    ------
    ValueError
        A bad argument, named; ``rmse``'s methods and entries beyond the work budget (3,000 units a method, 2 an
        entry, measured), before any is converted.
    """
    rmse, t = (read_mapping(rmse, "rmse"), read_once(t, "t"))  # read once (fuzz 29a C5, fuzz 31a C3)
    instance_of(rmse, Mapping, "rmse")
    tt = as_array(t, "t", ndim=1)
    t_min = scalar(t_min, "t_min")
    # rule 17 on rmse's methods and their entries, before converting any (fuzz 40a, the class of its C6: the methods
    # were not counted, so one array given under many keys was read over and over): 11 ns an entry and 20 us a
    # method measured (4 of 2**24 entries; 20,000 of 404; the least of two calls, time.process_time, machine
    # shared), weighed 2 units and 3 LOOP_STEP
    work((len(rmse),), "rmse (its methods)", weight=3 * LOOP_STEP)
    entries = [given_entries(r, MAX_INPUT_ELEMENTS) for r in rmse.values()]
    units = 3 * LOOP_STEP * len(entries) + 2 * math.ceil(sum(min(n, MAX_INPUT_ELEMENTS + 1) for n in entries
                                                             if n is not None))
    work((units,), "rmse (its methods and scans)")
    # an array-like with only __array__ has no size before it is converted (fuzz 41a C7: 400 methods of 2**23 entries
    # were not counted, and ended in a MemoryError after 7.5-10.8 CPU-s), and one with a shape may lie (fuzz 42a C13):
    # each value not an ndarray, list or tuple is converted once, one at a time, before any check, and counted, its
    # array held to the memory budget, refused as soon as the running total passes either
    values, held = [], 0
    for (name, r), given in zip(rmse.items(), entries):
        if not isinstance(r, (np.ndarray, list, tuple)):  # its shape may lie (fuzz 42a C13): the converted array counts
            try:
                r = np.asarray(r)
            except Exception:  # noqa: BLE001 (the check below converts it again and names it)
                pass
            else:
                counted = 0 if given is None else math.ceil(min(given, MAX_INPUT_ELEMENTS + 1))
                units, held = units + 2 * max(r.size - counted, 0), held + r.size
                work((units,), "rmse (its methods and scans)")
                allocation((held,), "rmse (its methods and scans)")
        values.append((name, r))
    checked = {}  # the arrays the checks return are what the means read (fuzz 31a C2: a DataFrame, a list of lists)
    for name, r in values:
        name = text_key(name, "rmse")   # a method's label keys the result: its text (fuzz 33a C5)
        checked[name] = a = as_array(r, f"rmse[{shown(name)}]", shape=(None, 4))
        if len(a) != tt.size:
            raise ValueError(f"rmse[{shown(name)}] must have one row per scan time in t ({tt.size}), got {len(a)}")
    late = tt >= t_min
    if not late.any():
        raise ValueError(f"t has no scan at or after t_min = {t_min} (last scan at {float(tt.max()):g})")
    return {name: {AZIMUTH_MRAD: 1e3 * float(r[late, 0].mean()), ELEVATION_MRAD: 1e3 * float(r[late, 1].mean()),
                   X_M: float(r[late, 2].mean()), Y_M: float(r[late, 3].mean())} for name, r in checked.items()}


#: Sensor sets of :func:`many_scan_bound`.
BOUND_SENSORS = ("infrared", "radar", "both")


def _sph_gradients(p: FloatArray) -> tuple[FloatArray, FloatArray, FloatArray]:
    """Gradients of range, azimuth and elevation with respect to the position, each (..., 3)."""
    x, y, z = p[..., 0], p[..., 1], p[..., 2]
    r = np.linalg.norm(p, axis=-1)
    rho = np.hypot(x, y)
    d_r = p / r[..., None]
    d_az = np.stack([-y / rho**2, x / rho**2, np.zeros_like(x)], axis=-1)
    d_el = np.stack([-x * z / (r**2 * rho), -y * z / (r**2 * rho), rho / r**2], axis=-1)
    return d_r, d_az, d_el


def many_scan_bound(
    path: Truth, sigma_ir: float, sigma_angle: float, sigma_range: float, sensors: str = "both",
    smoother: bool = False,
) -> FloatArray:
    r"""Cramér-Rao bound of azimuth, elevation, x and y for a target on a straight line, over many scans.

    The target flies :math:`\mathbf p(t) = \mathbf p_0 + \mathbf v t` with unknown
    :math:`\boldsymbol\theta = (\mathbf p_0, \mathbf v)` (6 parameters); each scan :math:`k` gives the
    infrared's azimuth and elevation (noise ``sigma_ir``) and/or the radar's range, azimuth and
    elevation (``sigma_range``, ``sigma_angle``), all independent Gaussian, sensors at the origin.
    The Fisher information of the scans up to :math:`k` is

    .. math:: J_k = \sum_{j \le k} A_j^\top G_j^\top W G_j A_j, \qquad A_j = [I_3,\; t_j I_3],

    with :math:`G_j` the gradient of :math:`(r, \alpha, \epsilon)` at :math:`\mathbf p(t_j)` and
    :math:`W` the inverse noise variances of the sensors used. For a quantity
    :math:`f(\mathbf p(t_k))` with gradient :math:`\mathbf g = \partial f/\partial\boldsymbol\theta`
    the bound on the variance of any unbiased estimator is :math:`\mathbf g^\top J_k^{-1}\mathbf g`
    (Van Trees 1968; Bar-Shalom, Li & Kirubarajan 2001, §2.7.2): the causal (filtering) bound. With
    ``smoother=True`` every scan counts (:math:`J_K` at every :math:`k`). With the infrared alone the
    range is not observable (:math:`J\boldsymbol\theta = 0`: scaling the path leaves its angles
    unchanged); its angles still are, and their bound is computed on the complement of that
    direction, while x and y are infinite.

    It applies to estimators of *this* model: a straight constant-velocity flight, the printed
    noise, both sensors at the origin. It knows the path is straight, which the chapter's
    angle-space filters do not.

    Parameters
    ----------
    path : Truth
        The true flight (:func:`truth`); it must be a straight constant-velocity line.
    sigma_ir, sigma_angle, sigma_range : float
        Infrared angle noise (rad), radar angle noise (rad), radar range noise (m), all > 0.
    sensors : {"infrared", "radar", "both"}
        Which measurements count.
    smoother : bool
        Bound from every scan (True) or from the scans up to each one (False, the filtering bound).

    Returns
    -------
    ndarray, shape (K, 4)
        Square roots of the bounds on azimuth (rad), elevation (rad), x (m) and y (m) at each scan;
        ``nan`` while the scans so far give fewer measurements than estimable parameters
        (6, or 5 with the infrared alone), ``inf`` for positions with the infrared alone.

    Raises
    ------
    ValueError
        ``path`` of more scans than the work or memory budget takes (750 units and 7 arrays of 36 float64 a scan,
        about 1e6 scans), refused before any work; a noise level not positive, an unknown sensor set, a path that is
        not a straight
        constant-velocity line, or noise levels so far apart in scale (each valid alone) that the
        information matrix is singular to working precision (condition number >= 1/eps).

    References
    ----------
    * Van Trees, H. L. (1968). *Detection, Estimation, and Modulation Theory, Part I*. Wiley.
    * Bar-Shalom, Y., Li, X. R., & Kirubarajan, T. (2001). *Estimation with Applications to
      Tracking and Navigation*. Wiley.
    """
    instance_of(path, Truth, "path")
    sensors = one_of(sensors, BOUND_SENSORS, "sensors")
    flag(smoother, "smoother")
    s_ir = std_scalar(sigma_ir, "sigma_ir")
    s_a = std_scalar(sigma_angle, "sigma_angle")
    s_r = std_scalar(sigma_range, "sigma_range")
    t, p = path.t, path.pos
    K = t.size
    # rules 17 and 9 on the path's scans K, before any work (fuzz 40a C3: truth accepts 10**7 scans; 3e6 ran 22.5
    # CPU-s, 1e7 a raw MemoryError on a 2.7 GiB (K, 6, 6) array)
    _scan_budget(K, "path (its scans K)")
    A = np.concatenate([np.broadcast_to(np.eye(3), (K, 3, 3)), t[:, None, None] * np.eye(3)], axis=-1)  # (K, 3, 6)
    theta, *_ = np.linalg.lstsq(A.reshape(-1, 6), p.reshape(-1), rcond=None)
    if not np.allclose(A @ theta, p, rtol=0.0, atol=1e-6 * max(1.0, float(np.abs(p).max()))):
        raise ValueError("path must be a straight constant-velocity line (p0 + v t)")
    d_r, d_az, d_el = (np.einsum("ki,kij->kj", d, A) for d in _sph_gradients(p))   # (K, 6) each
    w_angle = (1.0 / s_ir**2 if sensors != "radar" else 0.0) + (1.0 / s_a**2 if sensors != "infrared" else 0.0)
    w_range = 1.0 / s_r**2 if sensors != "infrared" else 0.0
    info = w_angle * (d_az[:, :, None] * d_az[:, None, :] + d_el[:, :, None] * d_el[:, None, :]) \
        + w_range * d_r[:, :, None] * d_r[:, None, :]
    J = np.broadcast_to(info.sum(axis=0), info.shape) if smoother else np.cumsum(info, axis=0)
    per_scan, n_par = (2, 5) if sensors == "infrared" else ((3, 6) if sensors == "radar" else (5, 6))
    n_meas = per_scan * (K if smoother else np.arange(1, K + 1))
    ok = np.broadcast_to(n_meas >= n_par, (K,))
    if sensors == "infrared":   # remove the unobservable scale direction (the angles do not depend on it)
        u = theta / np.linalg.norm(theta)
        J = J + np.trace(J, axis1=1, axis2=2)[:, None, None] * np.outer(u, u)
    G = np.stack([d_az, d_el, A[:, 0], A[:, 1]], axis=-1)   # (K, 6, 4)
    out = np.full((K, 4), np.nan)
    # noise levels of wildly different scales (each valid alone) leave an information matrix singular to
    # working precision: its inverse is rounding noise (a negative "variance", a NaN bound), refused by name
    names = {"infrared": "sigma_ir", "radar": "sigma_angle and sigma_range"}.get(
        sensors, "sigma_ir, sigma_angle and sigma_range")
    singular = ValueError(f"{names} are too far apart in scale: the information matrix of the scans is singular "
                          "to working precision, so the bound would be rounding noise")
    if np.any(ok) and not np.all(np.linalg.cond(J[ok]) < 1.0 / np.finfo(float).eps):
        raise singular
    try:
        sol = np.linalg.solve(J[ok], G[ok])
    except np.linalg.LinAlgError:
        raise singular from None
    q = np.einsum("kij,kij->kj", G[ok], sol)
    if not np.all(q > 0):   # a negative or NaN "variance"
        raise singular
    out[ok] = np.sqrt(q)
    if sensors == "infrared":
        out[:, 2:] = np.inf
    return out


def conversion_jacobian(sph: ArrayLike) -> FloatArray:
    r"""Jacobian of :func:`spherical_to_cartesian`: columns :math:`\partial\mathbf p/\partial r`, :math:`\partial\mathbf p/\partial\alpha`, :math:`\partial\mathbf p/\partial\epsilon`.

    A converted measurement :math:`\mathbf p(r, \alpha, \epsilon)` with independent noise
    :math:`\sigma_r, \sigma_\alpha, \sigma_\epsilon` has, to first order, the covariance
    :math:`J\,\mathrm{diag}(\sigma_r^2, \sigma_\alpha^2, \sigma_\epsilon^2)J^\top` (the linearised
    converted-measurement Kalman filter; Bar-Shalom, Li & Kirubarajan 2001, §10.4.3). The
    second-order bias, :math:`r(1 - e^{-\sigma^2/2}) \approx r\sigma^2/2`, is 0.2 m at 1 km for
    the radar's 0.02 rad and is neglected.

    Parameters
    ----------
    sph : array_like, shape (..., 3)
        Range (m), azimuth, elevation (rad).

    Returns
    -------
    ndarray, shape (..., 3, 3)
        At each ``sph``: the matrix whose columns are the derivatives of (x, y, z) by r, α and ε.

    Raises
    ------
    ValueError
        Wrong trailing shape or non-finite input.

    References
    ----------
    * Bar-Shalom, Y., Li, X. R., & Kirubarajan, T. (2001). *Estimation with Applications to
      Tracking and Navigation*. Wiley.
    """
    s = as_array(sph, "sph")
    if s.ndim < 1 or s.shape[-1] != 3:
        raise ValueError(f"sph must have shape (..., 3), got {s.shape}")
    r, az, el = s[..., 0], s[..., 1], s[..., 2]
    ca, sa, ce, se = np.cos(az), np.sin(az), np.cos(el), np.sin(el)
    cols = [np.stack([ce * ca, ce * sa, se], axis=-1),
            np.stack([-r * ce * sa, r * ce * ca, np.zeros_like(r)], axis=-1),
            np.stack([-r * se * ca, -r * se * sa, r * ce], axis=-1)]
    return np.stack(cols, axis=-1)


def _cv3(T: float) -> tuple[FloatArray, FloatArray]:
    """3-D constant-velocity model, state [x, vx, y, vy, z, vz]: F (6, 6) and H (3, 6)."""
    F = np.kron(np.eye(3), np.array([[1.0, T], [0.0, 1.0]]))
    H = np.kron(np.eye(3), np.array([[1.0, 0.0]]))
    return F, H


@dataclass(frozen=True)
class CartesianTracks:
    """Converted-measurement Cartesian tracks of :func:`cartesian_tracks`.

    Built with ``dataclasses.replace`` or directly, every field is checked (``fusion._results``):
    both tracks of the same runs and steps, state 6 and 3 readings, ``sigma_acc`` positive,
    ``r_change`` non-negative, ``source`` a string; otherwise a :class:`ValueError` naming the field.

    Attributes
    ----------
    radar : LocalTrack
        The radar's own (range, azimuth, elevation) converted to x, y, z; state [x, vx, y, vy, z, vz].
    ir : LocalTrack
        The infrared's angles with the radar's range of the same scan, converted.
    sigma_acc : float
        White-acceleration level of both filters (m/s²).
    r_change : float
        Largest relative change (Frobenius norm, over runs and scans) of the radar's converted
        covariance evaluated at the measured instead of the true geometry.
    source : str
        Fingerprint of the simulation the tracks were built from (:func:`cartesian_errors` refuses
        to score them against another one); empty if unknown.
    """

    radar: LocalTrack
    ir: LocalTrack
    sigma_acc: float
    r_change: float
    source: str = ""

    __result_spec__ = ResultSpec({"radar": nested(LocalTrack, runs="runs", K="K", n=6, m=3),
                                  "ir": nested(LocalTrack, runs="runs", K="K", n=6, m=3),
                                  "sigma_acc": number(positive=True), "r_change": number()})

    def __post_init__(self) -> None:
        instance_of(self.source, str, "CartesianTracks.source")
        validated_post_init(self)


def _fingerprint(sim: IrRadarRuns) -> str:
    """A digest of a simulation's times, truth and local estimates: tracks are tied to the simulation they came from."""
    h = hashlib.blake2b(digest_size=16)
    for a in (sim.t, sim.pos, sim.ir.est, sim.radar.est):
        arr = np.ascontiguousarray(a)
        h.update(str(arr.shape).encode())
        h.update(arr.tobytes())
    return h.hexdigest()


@derived_inputs()
def cartesian_tracks(sim: IrRadarRuns, sigma_acc: float = 1.0, velocity_sigma: float = 400.0) -> CartesianTracks:
    r"""Both sensors tracked in Cartesian coordinates from converted measurements (another reading of §3.5).

    The radar converts its own (range, azimuth, elevation); the infrared, which cannot range,
    converts its angles with the radar's range of the same scan (the usual infrared + radar
    pseudo-measurement). Each runs a 3-D constant-velocity Kalman filter with white acceleration
    ``sigma_acc`` per axis (the path is straight, so a small level fits) and covariance
    :math:`J\,\mathrm{diag}(\sigma_r^2, \sigma^2, \sigma^2)J^\top` (:func:`conversion_jacobian`),
    evaluated on the true geometry so that the gains are shared by the runs (``r_change`` says how
    little the measured geometry would change it). The range noise is common to both tracks, so
    its part of the covariance goes to the shared part of the split
    (:func:`fusion.filtering.kalman.split_covariances`), as do the process noise and the initial
    velocity; the angle noise is each sensor's own.

    Parameters
    ----------
    sim : IrRadarRuns
        Output of :func:`simulate`. Only its measurements (``ir.z``, ``radar.z``, ``radar_range.z``), its
        noise levels ``sigma``, the true geometry ``sph`` and the period ``t[1] - t[0]`` are used, not its
        angle-space filters (``est``, ``gains``, ``Pd``, ``Pi``), ``pos`` or ``sigma_acc``: those enter
        only the result's ``source`` fingerprint. Every field was checked when ``sim`` was built.
    sigma_acc : float
        White-acceleration level (m/s²), > 0.
    velocity_sigma : float
        Prior standard deviation of each velocity component (m/s), > 0; the filters start at the
        first converted measurement with zero velocity.

    Returns
    -------
    CartesianTracks
        The radar's and the infrared's Cartesian tracks (state [x, vx, y, vy, z, vz]), ``sigma_acc`` and the
        covariance's change ``r_change``.

    Raises
    ------
    ValueError
        ``sigma_acc`` or ``velocity_sigma`` not positive; ``sim``'s runs times scans beyond the work or memory budget
        (25,000 units a scan, 150 units and 54 float64 a run and scan: 1 run up to 39,761 scans, many runs about 5
        million run-scans), refused before any work; its ``sigma_range`` giving parts not semidefinite (2e5 m), naming sim.

    References
    ----------
    * Bar-Shalom, Y., Li, X. R., & Kirubarajan, T. (2001). *Estimation with Applications to
      Tracking and Navigation*. Wiley.
    """
    instance_of(sim, IrRadarRuns, "sim")
    q = std_scalar(sigma_acc, "sigma_acc")
    sv = std_scalar(velocity_sigma, "velocity_sigma")
    # rules 17 and 9 on sim's runs and scans, before any work (fuzz 40a C4: 110,000 runs of 101 scans ran 20 CPU-s)
    _tracks_budget(*sim.ir.est.shape[:2], "sim (its runs and scans)")
    T = float(sim.t[1] - sim.t[0])
    F, H = _cv3(T)
    Q = np.kron(np.eye(3), white_acceleration(T, q))
    Jt = conversion_jacobian(sim.sph)                      # (K, 3, 3), true geometry
    sr, sa, si = sim.sigma["range"], sim.sigma["angle"], sim.sigma["ir"]

    def cov(J: FloatArray, d: tuple[float, float, float]) -> FloatArray:
        return np.einsum("...ij,j,...kj->...ik", J, np.square(d), J)

    R_range = cov(Jt, (sr, 0.0, 0.0))
    zr = sim.radar_range.z[..., 0]
    tracks = []
    for angles, s in ((sim.radar.z, sa), (sim.ir.z, si)):
        z = _cartesian(zr, angles[..., 0], angles[..., 1])          # (runs, K, 3); a range below 0: as measured
        R_own = cov(Jt, (0.0, s, s))
        x0 = np.zeros((z.shape[0], 6))
        x0[:, 0::2] = z[:, 0]
        P0d = np.kron(np.eye(3), np.diag([0.0, sv**2])) + H.T @ R_range[0] @ H
        P0i = H.T @ R_own[0] @ H
        # its parts symmetric where a reader would refuse them (fuzz 43 C4: range noise 5,000 m)
        tracks.append(_symmetric_parts(_named_track("sim (its sigma_range) and velocity_sigma", z, F, H, Q, R_own, x0, P0d, P0i, R_shared=R_range)))
    _semidefinite_tracks(tracks, sr)  # the reader's semidefinite rule, naming sim (fuzz 44 C2: sigma_range 2e5 m)
    meas = np.stack([zr, sim.radar.z[..., 0], sim.radar.z[..., 1]], axis=-1)
    R_meas = cov(conversion_jacobian(meas), (sr, sa, sa))
    R_true = R_range + cov(Jt, (0.0, sa, sa))
    change = float(np.max(np.linalg.norm(R_meas - R_true, axis=(-2, -1)) / np.linalg.norm(R_true, axis=(-2, -1))))
    return trusted(CartesianTracks, radar=tracks[0], ir=tracks[1], sigma_acc=q, r_change=change, source=_fingerprint(sim))


def _errors(sim: IrRadarRuns, positions: FloatArray, angles: FloatArray) -> FloatArray:
    """Errors (runs, K, 4) of azimuth, elevation (rad), x, y (m)."""
    return np.stack([angles[..., 0] - sim.sph[:, 1], angles[..., 1] - sim.sph[:, 2],
                     positions[..., 0] - sim.pos[:, 0], positions[..., 1] - sim.pos[:, 1]], axis=-1)


#: Keys of the two Cartesian tracks in :func:`cartesian_errors`, by sensor.
CARTESIAN_LOCAL = constant({"radar": IrMethod.CARTESIAN_RADAR, "ir": IrMethod.CARTESIAN_IR})


def cartesian_errors(sim: IrRadarRuns, tracks: CartesianTracks, rules: Sequence[str] | None = None) -> dict[IrMethod, FloatArray]:
    """Errors of the two Cartesian tracks and of each rule of :data:`RULES` fusing them.

    Parameters
    ----------
    sim : IrRadarRuns
        The simulation the tracks were built from.
    tracks : CartesianTracks
        Output of :func:`cartesian_tracks`.
    rules : sequence of str, optional
        Keys of :data:`RULES` to run (default: all).

    Returns
    -------
    dict of IrMethod to ndarray, shape (runs, K, 4)
        Errors of azimuth (rad), elevation (rad), x (m), y (m); angles from the estimated position.

    Raises
    ------
    ValueError
        A key in ``rules`` that is not in :data:`RULES` or is named twice (more entries than RULES: by the length);
        ``tracks`` built from another simulation than ``sim`` (other runs, scans or draws); their runs times scans
        beyond the work, memory or input budget of this reading (355 units a run and scan with every rule, about 2.8
        million), refused before any work.
    """
    instance_of(sim, IrRadarRuns, "sim")
    instance_of(tracks, CartesianTracks, "tracks")
    if tracks.radar.est.shape[:2] != sim.ir.est.shape[:2] or (tracks.source and tracks.source != _fingerprint(sim)):
        raise ValueError(f"tracks were built from another simulation than sim (tracks of shape {tracks.radar.est.shape[:2]} "
                         f"for runs x scans {sim.ir.est.shape[:2]}, or other draws): pass cartesian_tracks(sim)")
    subset = _rule_subset(rules)
    _reader_budget("cartesian_errors", *tracks.ir.est.shape, subset, "sim and tracks (their runs and scans) and rules")
    est = {CARTESIAN_LOCAL["radar"]: tracks.radar.est, CARTESIAN_LOCAL["ir"]: tracks.ir.est}
    for name, rule in subset.items():
        est[name] = fuse_tracks(tracks.ir, tracks.radar, rule).est
    out = {}
    for name, e in est.items():
        p = e[..., 0::2]
        out[name] = _errors(sim, p, cartesian_to_spherical(p)[..., 1:])
    return out
