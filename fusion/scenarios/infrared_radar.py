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

from collections.abc import Mapping
from dataclasses import dataclass

import numpy as np
from filterpy.common import Q_discrete_white_noise
from numpy.typing import ArrayLike

from fusion._frozen import freeze_arrays
from fusion._validation import FloatArray, as_array, as_rng, count, instance_of, nonnegative_scalar, positive_scalar, scalar
from fusion.filtering.tracks import LocalTrack, fuse_tracks, local_track
from fusion.filtering.kalman import cv_model

__all__ = [
    "Truth",
    "spherical_to_cartesian",
    "cartesian_to_spherical",
    "truth",
    "white_acceleration",
    "IrRadarRuns",
    "simulate",
    "position",
    "RULES",
    "PER_SCAN",
    "rule_errors",
    "rmse_by_rule",
    "late_means",
]


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
        Non-finite inputs.
    """
    r, az, el = (as_array(v, n, nonempty=False) for v, n in ((r, "r"), (az, "az"), (el, "el")))
    if np.any(r < 0):
        raise ValueError("r (range) must be non-negative")
    try:
        np.broadcast_shapes(r.shape, az.shape, el.shape)
    except ValueError:
        raise ValueError(f"r, az and el must broadcast together, got shapes {r.shape}, {az.shape}, {el.shape}") from None
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
        raise ValueError("the angles of a target at the sensor are undefined (range 0)")
    return np.stack([r, np.arctan2(p[..., 1], p[..., 0]), np.arcsin(p[..., 2] / r)], axis=-1)


@dataclass(frozen=True)
class Truth:
    """True trajectory: times, Cartesian and spherical positions.

    Arrays are read-only.

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

    __post_init__ = freeze_arrays


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
    t = np.arange(0.0, duration + 1e-9, T)
    v = np.asarray(velocity, dtype=float)
    if v.shape != (3,) or not np.all(np.isfinite(v)):
        raise ValueError(f"velocity must be 3 finite numbers (m/s), got {velocity!r}")
    p0 = spherical_to_cartesian(positive_scalar(r0, "r0"), scalar(az0, "az0"), scalar(el0, "el0"))
    pos = p0 + t[:, None] * v
    return Truth(t=t, pos=pos, sph=cartesian_to_spherical(pos))


def white_acceleration(T: float, sigma: float) -> FloatArray:
    r"""Discrete white-noise-acceleration covariance of one :math:`[p, \dot p]` pair.

    :math:`\sigma^2\begin{bmatrix}T^4/4 & T^3/2\\ T^3/2 & T^2\end{bmatrix}` (``sigma`` in units/s²;
    Bar-Shalom, Li & Kirubarajan 2001).

    Parameters
    ----------
    T : float
        Sampling period (s), > 0.
    sigma : float
        Standard deviation of the piecewise-constant acceleration, >= 0: ``sigma = 0`` (no
        acceleration, e.g. a stationary target) gives the zero matrix, a valid positive-semidefinite
        process noise.

    Returns
    -------
    ndarray, shape (2, 2)

    Raises
    ------
    ValueError
        ``T`` not positive or ``sigma`` negative.
    """
    T = positive_scalar(T, "T")
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

    Attributes
    ----------
    t : ndarray, shape (K,)
    pos, sph : ndarray, shape (K, 3)
        True position (m) and range/azimuth/elevation (m, rad).
    ir, radar : LocalTrack
        Angle tracks, state [az, az rate, el, el rate].
    radar_range : LocalTrack
        The radar's range track, state [r, r rate].
    sigma_acc : dict
        Process-noise levels used (rad/s² for the angles, m/s² for range).
    """

    t: FloatArray
    pos: FloatArray
    sph: FloatArray
    ir: LocalTrack
    radar: LocalTrack
    radar_range: LocalTrack
    sigma_acc: dict[str, float]


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
    **geometry
        Passed to :func:`truth` (``r0``, ``az0``, ``el0``, ``velocity``).

    Returns
    -------
    IrRadarRuns
        Truth and the three local tracks of every run.

    Raises
    ------
    ValueError
        ``runs`` not positive, fewer than three samples, a noise level not positive, or bad
        geometry (see :func:`truth`).
    """
    as_rng(rng)
    runs = count(runs, "runs")
    rate_sigma = positive_scalar(rate_sigma, "rate_sigma")
    range_rate_sigma = positive_scalar(range_rate_sigma, "range_rate_sigma")
    true_path = truth(T, duration, **geometry)
    t, pos, sph = true_path.t, true_path.pos, true_path.sph
    if t.size < 3:
        raise ValueError("the track needs at least three samples (duration >= 2 T)")
    model = cv_model(T)
    F, H = model.F, model.H
    acc = {"az": _max_acceleration(sph[:, 1], T), "el": _max_acceleration(sph[:, 2], T),
           "range": _max_acceleration(sph[:, 0], T)}
    Q = _block(white_acceleration(T, acc["az"]), white_acceleration(T, acc["el"]))
    P0d = np.diag([0.0, rate_sigma**2, 0.0, rate_sigma**2])
    angles = sph[None, :, 1:]
    tracks = []
    for s in (positive_scalar(sigma_ir, "sigma_ir"), positive_scalar(sigma_angle, "sigma_angle")):
        z = angles + s * rng.standard_normal((runs, t.size, 2))
        x0 = np.column_stack([z[:, 0, 0], np.zeros(runs), z[:, 0, 1], np.zeros(runs)])
        tracks.append(local_track(z, F, H, Q, np.diag([s**2, s**2]), x0, P0d, np.diag([s**2, 0.0, s**2, 0.0])))
    sr = positive_scalar(sigma_range, "sigma_range")
    zr = sph[None, :, :1] + sr * rng.standard_normal((runs, t.size, 1))
    Fr, Hr = F[:2, :2], H[:1, :2]
    rng_track = local_track(zr, Fr, Hr, white_acceleration(T, acc["range"]), np.array([[sr**2]]),
                            np.column_stack([zr[:, 0, 0], np.zeros(runs)]),
                            np.diag([0.0, range_rate_sigma**2]), np.diag([sr**2, 0.0]))
    return IrRadarRuns(t=t, pos=pos, sph=sph, ir=tracks[0], radar=tracks[1], radar_range=rng_track, sigma_acc=acc)


def position(range_est: ArrayLike, angle_est: ArrayLike) -> FloatArray:
    """Cartesian position (..., 3) from range tracks (..., 2) and angle tracks (..., 4).

    Uses the range of ``range_est[..., 0]`` and the angles ``angle_est[..., 0]`` (azimuth) and
    ``angle_est[..., 2]`` (elevation) in :func:`spherical_to_cartesian`.

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
    return spherical_to_cartesian(r[..., 0], a[..., 0], a[..., 2])


#: The fusion rules compared in chapter 05, by display name (see :func:`fusion.filtering.tracks.fuse_tracks`).
RULES = {
    "CI (closed-form ω)": "ci",
    "improved CI (split CI)": "split",
    "convex comb. = multi-Bayesian = ML": "convex",
    "fuzzy clustering": "fuzzy",
}

#: Name of the unfiltered reference in :func:`rule_errors`.
PER_SCAN = "per scan, no filter: IR angles + radar range"


def rule_errors(sim: IrRadarRuns) -> dict[str, FloatArray]:
    """Errors of each sensor alone, each rule of :data:`RULES`, and the unfiltered reference.

    Every rule fuses the two angle tracks; positions use the radar's range track. The reference
    :data:`PER_SCAN` takes each scan's raw infrared angles with the radar's raw range (no filter).

    Parameters
    ----------
    sim : IrRadarRuns
        Output of :func:`simulate`.

    Returns
    -------
    dict of str to ndarray, shape (runs, K, 4)
        Errors of azimuth (rad), elevation (rad), x (m), y (m).
    """
    instance_of(sim, IrRadarRuns, "sim")
    angle_tracks = {"infrared alone": sim.ir.est, "radar alone": sim.radar.est}
    for name, rule in RULES.items():
        angle_tracks[name] = fuse_tracks(sim.ir, sim.radar, rule).est
    out = {}
    for name, est in angle_tracks.items():
        p = position(sim.radar_range.est, est)
        out[name] = np.stack([est[..., 0] - sim.sph[:, 1], est[..., 2] - sim.sph[:, 2],
                              p[..., 0] - sim.pos[:, 0], p[..., 1] - sim.pos[:, 1]], axis=-1)
    raw = spherical_to_cartesian(sim.radar_range.z[..., 0], sim.ir.z[..., 0], sim.ir.z[..., 1])
    out[PER_SCAN] = np.stack([sim.ir.z[..., 0] - sim.sph[:, 1], sim.ir.z[..., 1] - sim.sph[:, 2],
                              raw[..., 0] - sim.pos[:, 0], raw[..., 1] - sim.pos[:, 1]], axis=-1)
    return out



def rmse_by_rule(sim: IrRadarRuns) -> dict[str, FloatArray]:
    """RMSE over the runs per scan of each entry of :func:`rule_errors`.

    Parameters
    ----------
    sim : IrRadarRuns
        Output of :func:`simulate`.

    Returns
    -------
    dict of str to ndarray, shape (K, 4)
        Azimuth (rad), elevation (rad), x (m), y (m).
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
    """
    instance_of(rmse, Mapping, "rmse")
    tt = as_array(t, "t", ndim=1)
    t_min = scalar(t_min, "t_min")
    for name, r in rmse.items():
        as_array(r, f"rmse[{name!r}]", shape=(None, 4))
        if len(r) != tt.size:
            raise ValueError(f"rmse[{name!r}] must have one row per scan time in t ({tt.size}), got {len(r)}")
    late = np.asarray(t, dtype=float) >= t_min
    if not late.any():
        raise ValueError(f"no scan at or after t_min = {t_min}")
    return {name: {"azimuth (mrad)": 1e3 * float(r[late, 0].mean()), "elevation (mrad)": 1e3 * float(r[late, 1].mean()),
                   "x (m)": float(r[late, 2].mean()), "y (m)": float(r[late, 3].mean())} for name, r in rmse.items()}
