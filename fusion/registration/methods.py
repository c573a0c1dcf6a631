r"""Time registration (时间配准): a fast sensor's samples onto a slow sensor's instants.

Shi, Suo & Ma (2023) register the samples :math:`z_i` of sensor 1, taken at
strictly increasing times :math:`t_i`, onto the sampling instants :math:`t_k` of sensor 2.
Its equations (1)-(9) were lost in extraction; every formula here is **rebuilt** from the
literature the source cites (see the chapter):

* :func:`two_point`: interpolation/extrapolation (内插外推法), constant velocity;
* :func:`three_point`: three-point Lagrange interpolation, constant acceleration (eqs. 7-9);
* :func:`least_squares` and :func:`blair_ls`: the least-squares registration of Blair et al. (1991);
* :func:`kalman_filter` / :func:`kalman_register`: the constant-acceleration Kalman filter of
  eqs. (1)-(6) and the registration of §3 (predict the last estimate to the instant);
* :func:`improved_register`: the proposal of §4 (filter, then three-point interpolation).

Every method is affine in the measurements (the Kalman gains do not depend on the data), so
:func:`fusion.registration.analysis.affine_decomposition` and
:func:`fusion.registration.analysis.expected_mse` give exact error statistics.

References
----------
* Shi, J., Suo, X., & Ma, S. (2023). Time registration technology for heterogeneous sensors.
  *Computer Programming Skills & Maintenance*, 2023(4) (in Chinese).
* Blair, W. D., Rice, T. R., Alouani, A. T., & Xia, P. (1991). Asynchronous data fusion for
  target tracking with a multitasking radar and optical sensor. In *Acquisition, Tracking, and
  Pointing V*, Proceedings of SPIE, 1482.
* Kalman, R. E. (1960). A new approach to linear filtering and prediction problems.
  *Journal of Basic Engineering*, 82(1), 35-45.
* Bar-Shalom, Y., Li, X. R., & Kirubarajan, T. (2001). *Estimation with Applications to
  Tracking and Navigation*. Wiley.
"""

from __future__ import annotations

from dataclasses import dataclass


import numpy as np
from filterpy.common import Q_continuous_white_noise, Q_discrete_white_noise
from filterpy.kalman import KalmanFilter
from numpy.typing import ArrayLike
from scipy.interpolate import CubicSpline

from fusion._frozen import frozen_arrays
from fusion._validation import derived_inputs
from fusion._validation import flag
from fusion._validation import LOOP_STEP, loop_work
from fusion._validation import (as_times, _numeric, FloatArray, as_array, check_magnitude, count, nonnegative_scalar,
                                one_of, positive_scalar, scalar, std_scalar, step_scalar)
from fusion._validation import MAX_MAGNITUDE, MIN_VARIANCE, finite_result, grid_points
from fusion._shown import shown

__all__ = [
    "FilteredStates",
    "Q_MODELS",
    "INITS",
    "process_noise",
    "kalman_runs",
    "quadratic_ls",
    "spline_register",
    "BlairEstimate",
    "two_point",
    "three_point",
    "least_squares",
    "blair_ls",
    "ca_transition",
    "kalman_filter",
    "kalman_register",
    "predict_to",
    "improved_register",
    "sample_times",
]


# --------------------------------------------------------------------------- validation


def _series(t: ArrayLike, z: ArrayLike, min_len: int) -> tuple[FloatArray, FloatArray]:
    tt = _numeric(t, "t")
    zz = _numeric(z, "z")
    if tt.ndim != 1 or zz.ndim != 1:
        raise ValueError(f"t and z must be 1-D, got shapes {tt.shape} and {zz.shape}")
    if tt.shape != zz.shape:
        raise ValueError(f"t and z must have equal lengths, got {tt.size} and {zz.size}")
    if tt.size < min_len:
        raise ValueError(f"t and z must hold at least {min_len} samples, got {tt.size}")
    as_times(tt, "t")
    check_magnitude(zz, "z")
    return tt, zz


def _query(t_query: ArrayLike) -> FloatArray:
    q = np.atleast_1d(_numeric(t_query, "t_query"))
    if q.ndim != 1 or q.size == 0:
        raise ValueError(f"t_query must be a non-empty 1-D array, got shape {q.shape}")
    check_magnitude(q, "t_query")
    return q


def sample_times(first: float, period: float, end: float) -> FloatArray:
    """Sampling instants ``first, first + period, ...`` not later than ``end`` (s).

    :math:`t_j = \\text{first} + j\\,\\text{period}`, :math:`j = 0, 1, \\dots` while
    :math:`t_j \\le \\text{end}` (with a 1e-9 relative allowance for round-off).

    Parameters
    ----------
    first : float
        First instant (s).
    period : float
        Sampling period (s), > 0.
    end : float
        Last admissible instant (s), ``end >= first``.

    Returns
    -------
    ndarray, shape (n,)
        The instants in seconds.

    Raises
    ------
    ValueError
        ``period`` not positive, non-finite bounds or ``end < first``; ``period`` so small against the floats at
        ``first`` and ``end`` that two instants would round to the same float (they must strictly increase).
    """
    period = positive_scalar(period, "period")
    first, end = scalar(first, "first"), scalar(end, "end")
    if end < first:
        raise ValueError(f"need first <= end, got first={shown(first)}, end={shown(end)}")
    grid_points(end - first, period, "first, end and period")  # rule 9: refused by name before np.arange
    n = int(np.floor((end - first) / period + 1e-9)) + 1
    t = first + period * np.arange(n)
    # a period below the spacing of floats at first/end rounds some instants onto their predecessor, which every
    # reader (two_point, three_point, spline_register) refuses as not strictly increasing (fuzz 45 C4: 1e6, 1e-10,
    # 1e6 + 1e-8 gave 14 repeats); O(n) on instants the grid budget already bounds
    if n > 1 and not (t[1:] > t[:-1]).all():
        spacing = float(np.spacing(max(abs(first), abs(end))))
        raise ValueError(f"period = {shown(period)} s is too small against the spacing of floats at first = "
                         f"{shown(first)} s and end = {shown(end)} s ({shown(spacing)} s): the instants first + j "
                         f"period would repeat; they must strictly increase")
    return t


# --------------------------------------------------------------------------- interpolation


def two_point(t: ArrayLike, z: ArrayLike, t_query: ArrayLike, causal: bool = False) -> FloatArray:
    r"""Two-point interpolation/extrapolation (constant velocity).

    .. math:: \hat z(t) = z_i + \frac{t - t_i}{t_{i+1} - t_i}(z_{i+1} - z_i),
              \qquad t_i \le t < t_{i+1},

    with the first (last) two samples used before (beyond) the data. With ``causal=True``
    the line goes through the last two samples not later than :math:`t` (extrapolation,
    no future sample; the first two samples before the second sample time).

    Parameters
    ----------
    t, z : array_like, shape (n,), n >= 2
        Strictly increasing sample times (s) and samples (m).
    t_query : array_like, shape (K,)
        Registration instants (s).
    causal : bool
        Extrapolate from the past instead of interpolating.

    Returns
    -------
    ndarray, shape (K,)
        Registered values (m).
    """
    flag(causal, "causal")
    tt, zz = _series(t, z, 2)
    q = _query(t_query)
    i = np.searchsorted(tt, q, side="right") - (2 if causal else 1)
    i = np.clip(i, 0, tt.size - 2)
    return zz[i] + (q - tt[i]) / (tt[i + 1] - tt[i]) * (zz[i + 1] - zz[i])


def three_point(t: ArrayLike, z: ArrayLike, t_query: ArrayLike, causal: bool = False) -> FloatArray:
    r"""Three-point Lagrange interpolation (constant acceleration; source eqs. 7-9, rebuilt).

    .. math:: \hat z(t) = \sum_{m} z_m \prod_{l \ne m} \frac{t - t_l}{t_m - t_l}

    over the nodes :math:`(t_{j-1}, t_j, t_{j+1})` with :math:`t_j \le t < t_{j+1}`, shifted
    inward at both ends. It is the unique quadratic through the three samples, hence exact on
    any constant-acceleration motion. With ``causal=True`` the nodes are the last three
    samples not later than :math:`t` (extrapolation, no future sample).

    Parameters
    ----------
    t, z : array_like, shape (n,), n >= 3
    t_query : array_like, shape (K,)
    causal : bool

    Returns
    -------
    ndarray, shape (K,)
        The interpolated values at the ``t_query`` instants.

    Examples
    --------
    Exact on a constant-acceleration motion, between samples and, with ``causal=True``, ahead of
    the last three samples used:

    >>> import numpy as np
    >>> from fusion.registration.methods import three_point
    >>> t = np.arange(5.0)
    >>> z = 1 + 2 * t + 0.5 * t**2
    >>> three_point(t, z, [0.5, 2.25])
    array([2.125  , 8.03125])
    >>> three_point(t, z, [2.5], causal=True)  # from the samples at t = 0, 1, 2
    array([9.125])
    """
    flag(causal, "causal")
    tt, zz = _series(t, z, 3)
    q = _query(t_query)
    j = np.searchsorted(tt, q, side="right") - 1  # t_j <= q < t_{j+1}
    if causal:
        centre = j - 1
    else:
        centre = j
    centre = np.clip(centre, 1, tt.size - 2)
    nodes = np.stack([centre - 1, centre, centre + 1], axis=1)  # (K, 3)
    tn, zn = tt[nodes], zz[nodes]
    out = np.zeros(q.size)
    for m in range(3):
        basis = np.ones(q.size)
        for l in range(3):
            if l != m:
                basis *= (q - tn[:, l]) / (tn[:, m] - tn[:, l])
        out += zn[:, m] * basis
    return out


# --------------------------------------------------------------------------- least squares


@dataclass(frozen=True)
@frozen_arrays
class BlairEstimate:
    """Least-squares position and velocity at the last sample of a block.

    Arrays are read-only.

    Attributes
    ----------
    z : float
        Position at the last sample (m).
    zdot : float
        Velocity (m/s).
    """

    z: float
    zdot: float


def blair_ls(z_block: ArrayLike, tau: float) -> BlairEstimate:
    r"""Blair et al. (1991) least-squares registration of ``n`` equally spaced samples.

    Model :math:`z_i = z + (i - n)\tau\dot z + v_i`, :math:`i = 1..n` (the last sample at the
    registration instant). With :math:`S_1 = \sum z_i`, :math:`S_2 = \sum i z_i`:

    .. math:: \hat z = -\frac{2}{n}S_1 + \frac{6}{n(n+1)}S_2, \qquad
              \hat{\dot z} = \frac{6(2S_2 - (n+1)S_1)}{n(n^2 - 1)\tau}.

    Parameters
    ----------
    z_block : array_like, shape (n,), n >= 2
        The last ``n`` samples (m), equally spaced, the last at the registration instant.
    tau : float
        Sampling period of the fast sensor (s).

    Returns
    -------
    BlairEstimate
        ``z`` and ``zdot``.

    Raises
    ------
    ValueError
        Fewer than two samples, non-finite samples, ``tau`` not positive.

    References
    ----------
    * Blair, W. D., Rice, T. R., Alouani, A. T., & Xia, P. (1991). Asynchronous data fusion for
      target tracking with a multitasking radar and optical sensor. In *Acquisition, Tracking, and
      Pointing V*, Proceedings of SPIE, 1482.
    """
    zb = _numeric(z_block, "z_block")
    if zb.ndim != 1 or zb.size < 2:
        raise ValueError("z_block must be a finite 1-D array of at least 2 samples")
    check_magnitude(zb, "z_block")
    tau = positive_scalar(tau, "tau")
    n = zb.size
    i = np.arange(1, n + 1)
    s1, s2 = zb.sum(), (i * zb).sum()
    z_hat = -2.0 / n * s1 + 6.0 / (n * (n + 1)) * s2
    zdot = 6.0 * (2 * s2 - (n + 1) * s1) / (n * (n**2 - 1) * tau)
    return BlairEstimate(z=float(z_hat), zdot=float(zdot))


def least_squares(t: ArrayLike, z: ArrayLike, t_query: ArrayLike, window: float) -> FloatArray:
    r"""Least-squares registration on a time window (Blair et al. 1991, generalised).

    For each instant :math:`t_k`, fit :math:`\alpha + \beta(s - t_k)` by least squares to the
    samples in :math:`(t_k - \text{window}, t_k]` and return :math:`\alpha`. With an integer
    period ratio and a sample at :math:`t_k` this is :func:`blair_ls`; with a non-integer
    ratio (5 s / 2 s in Shi, Suo & Ma 2023) the number of samples per window and their position vary,
    and the fit extrapolates from the last sample to :math:`t_k`.

    Parameters
    ----------
    t, z : array_like, shape (n,)
        Sample times (s, strictly increasing) and measurements (m) of the fast sensor.
    t_query : array_like, shape (K,)
        Registration instants (s).
    window : float
        Window length (s), normally the slow sensor's period.

    Returns
    -------
    ndarray, shape (K,)
        Registered values :math:`\alpha` at each instant (m).

    Raises
    ------
    ValueError
        If a window holds fewer than two samples, times are not strictly increasing or not
        finite, or ``window`` is not positive.

    References
    ----------
    * Blair, W. D., Rice, T. R., Alouani, A. T., & Xia, P. (1991). Asynchronous data fusion for
      target tracking with a multitasking radar and optical sensor. In *Acquisition, Tracking, and
      Pointing V*, Proceedings of SPIE, 1482.
    """
    tt, zz = _series(t, z, 2)
    q = _query(t_query)
    window = positive_scalar(window, "window")
    # rule 17: a least-squares fit per query (~10 loop steps of numpy calls) over a mask of every sample
    loop_work((q.size,), 4 * tt.size, "t_query and t", step=10 * LOOP_STEP)
    out = np.empty(q.size)
    for k, tk in enumerate(q):
        sel = (tt > tk - window) & (tt <= tk)
        if sel.sum() < 2:
            raise ValueError(f"t_query[{k}] = {tk:g}: the window ({tk - window:g}, {tk:g}] s holds fewer than 2 "
                             "samples of t (widen window or query inside the data)")
        W = np.column_stack([np.ones(sel.sum()), tt[sel] - tk])
        coef, *_ = np.linalg.lstsq(W, zz[sel], rcond=None)
        out[k] = coef[0]
    return out


# --------------------------------------------------------------------------- Kalman filter


def ca_transition(dt: float) -> FloatArray:
    r"""Constant-acceleration transition :math:`\Phi(T)` of state :math:`[x, \dot x, \ddot x]`.

    .. math:: \Phi(T) = \begin{bmatrix}1 & T & T^2/2\\ 0 & 1 & T\\ 0 & 0 & 1\end{bmatrix}

    (the transition of Shi, Suo & Ma (2023), eqs. (1)-(6), rebuilt; Bar-Shalom, Li & Kirubarajan 2001).

    Parameters
    ----------
    dt : float
        Time step :math:`T` in seconds (any sign: a negative step predicts backwards).

    Returns
    -------
    ndarray, shape (3, 3)
        [[1, dt, dt²/2], [0, 1, dt], [0, 0, 1]].
    """
    dt = scalar(dt, "dt")
    return np.array([[1.0, dt, 0.5 * dt * dt], [0.0, 1.0, dt], [0.0, 0.0, 1.0]])


#: Readings of the driving noise :math:`Q` (see :func:`process_noise`).
Q_MODELS: tuple[str, ...] = ("per-step", "white-noise jerk", "Wiener-process acceleration")
#: Readings of the initialisation (see :func:`kalman_filter`).
INITS: tuple[str, ...] = ("source", "once")


def process_noise(dt: float, q_v: float, q_a: float, model: str = "per-step", period: float = 2.0) -> FloatArray:
    r"""Driving-noise covariance :math:`Q` of the constant-acceleration filter for a step ``dt``.

    * ``"per-step"`` — the text of Shi, Suo & Ma (2023, eq. 3 rebuilt):
      :math:`Q = \Gamma\,\mathrm{diag}(q_v, q_a)\Gamma^\top = \mathrm{diag}(0, q_v, q_a)` added at
      every step *whatever its length*. This is not one of Bar-Shalom's constant-acceleration
      models: it does not scale with the step, so splitting a step in two doubles the noise.
    * ``"white-noise jerk"`` — the continuous white-noise jerk model discretised exactly
      (Bar-Shalom, Li & Kirubarajan 2001, §6.2.3; ``filterpy.common.Q_continuous_white_noise``)
      with spectral density :math:`\tilde q = q_a/\text{period}`, so that the acceleration
      variance added over one nominal period is :math:`q_a`. Splitting a step changes nothing:
      :math:`Q(T_1 + T_2) = \Phi(T_2)Q(T_1)\Phi(T_2)^\top + Q(T_2)`.
    * ``"Wiener-process acceleration"`` — Bar-Shalom's discrete Wiener-process acceleration model
      (Bar-Shalom et al. 2001, §6.3.3; ``filterpy.common.Q_discrete_white_noise``), white acceleration
      *increments*: :math:`Q = q_a\,g g^\top`, :math:`g = [T^2/2, T, 1]^\top`. Its position and velocity
      terms scale with the step, but the acceleration variance added per step is :math:`q_a` whatever
      :math:`T`, and it is not exactly additive.

    ``q_v`` is used by the per-step model only: the other two models have no separate velocity noise, so
    they differ from the per-step model in noise content as well as in form.

    Parameters
    ----------
    dt : float
        Step length (s), >= 0 and at most ``1e150 ** (1/5)`` (the white-noise-jerk model forms ``dt**5``).
    q_v, q_a : float
        Variances (m²/s², m²/s⁴), >= 0.
    model : str
        One of :data:`Q_MODELS`.
    period : float
        Nominal sampling period (s), > 0, that calibrates the white-noise-jerk density.

    Returns
    -------
    ndarray, shape (3, 3)
        diag(0, q_v, q_a) for ``"per-step"``, else filterpy's white-noise-jerk or discrete white-noise matrix.

    Raises
    ------
    ValueError
        Unknown ``model``, negative ``dt``, ``q_v`` or ``q_a``, non-positive ``period``.

    References
    ----------
    * Bar-Shalom, Y., Li, X. R., & Kirubarajan, T. (2001). *Estimation with Applications to
      Tracking and Navigation*. Wiley.
    """
    dt = step_scalar(dt, "dt", 5, zero=True)
    q_v, q_a = nonnegative_scalar(q_v, "q_v"), nonnegative_scalar(q_a, "q_a")
    period = positive_scalar(period, "period")
    model = one_of(model, Q_MODELS, "model")
    if model == "per-step":
        return np.diag([0.0, q_v, q_a])
    if model == "white-noise jerk":
        return np.asarray(Q_continuous_white_noise(3, dt=dt, spectral_density=q_a / period), dtype=float)
    return np.asarray(Q_discrete_white_noise(3, dt=dt, var=q_a), dtype=float)


@dataclass(frozen=True)
@frozen_arrays
class FilteredStates:
    """Filtered states and their covariances at the sample times.

    Arrays are read-only.

    Attributes
    ----------
    x : ndarray, shape (n, 3), or (runs, n, 3) for a batch of runs
        Filtered (or smoothed) states at the sample times.
    P : ndarray, shape (n, 3, 3)
        Their covariances (the same for every run: the gains do not depend on the data).
    """

    x: FloatArray
    P: FloatArray


def _kf_options(sigma: float, q_v: float, q_a: float, q_model: str, init: str, p0: tuple[float, float],
                period: float) -> tuple[float, float, float, str, str, tuple[float, float], float]:
    sigma = std_scalar(sigma, "sigma")
    q_v, q_a = nonnegative_scalar(q_v, "q_v"), nonnegative_scalar(q_a, "q_a")
    q_model = one_of(q_model, Q_MODELS, "q_model")
    init = one_of(init, INITS, "init")
    pv = _numeric(p0, "p0")
    if pv.shape != (2,) or not np.all(np.isfinite(pv)) or np.any(pv <= 0):
        raise ValueError(f"p0 must be two positive finite variances (velocity, acceleration), got {shown(p0)}")
    if not (float(pv.max()) <= MAX_MAGNITUDE and float(pv.min()) >= MIN_VARIANCE):  # the covariance rule
        raise ValueError(f"p0 must be two variances within [{MIN_VARIANCE:.3g}, {MAX_MAGNITUDE:g}], got {shown(p0)}")
    period = positive_scalar(period, "period")
    return sigma, q_v, q_a, q_model, init, (float(pv[0]), float(pv[1])), period


#: Longest step between two instants of the filter's grid: the white-noise-jerk model forms ``dt**5``.
MAX_STEP = MAX_MAGNITUDE ** 0.2


def _grid(tt: FloatArray, t_extra: ArrayLike | None) -> tuple[FloatArray, np.ndarray]:
    """Union of the sample times and extra prediction instants; mask of the sample nodes."""
    if t_extra is None:
        return tt, np.ones(tt.size, dtype=bool)
    ex = np.atleast_1d(_numeric(t_extra, "t_extra"))
    if ex.ndim != 1:
        raise ValueError(f"t_extra must be a finite 1-D array, got shape {ex.shape}")
    check_magnitude(ex, "t_extra")
    ex = ex[(ex > tt[0]) & ~np.isin(ex, tt)]
    g = np.union1d(tt, ex)
    if g.size > 1 and not float(np.max(np.diff(g))) <= MAX_STEP:  # the model forms dt**5 (process_noise)
        raise ValueError(f"t and t_extra leave a step beyond {MAX_STEP:.3g} s between instants: the model forms "
                         "powers of the step up to the 5th, which must stay representable")
    return g, np.isin(g, tt)


#: Units (about 10 ns, ``fusion._limits.MAX_WORK``) of one grid step of the Kalman filter's Python loop (a sample or
#: an instant of ``t_extra``): :func:`kalman_filter`'s filterpy step measured 20-28 us, :func:`kalman_runs`' 26 us
#: (50,000 samples, one run; ``time.process_time``, ``OPENBLAS_NUM_THREADS=1``, the least of two, the machine shared
#: with other jobs; fuzz 53b C4: 31 CPU-s at 1,000,000 samples were accepted, ~1,000 at the input cap).
_KALMAN_STEP = 3 * LOOP_STEP
#: Units of one grid step with the smoother's backward pass (``smooth`` or ``lag_one`` of :func:`kalman_runs`): the
#: filter and the pass measured 37-38 us a step (50,000 samples, one run).
_SMOOTHER_STEP = 4 * LOOP_STEP
#: Units of one run of :func:`kalman_runs` at one grid step, filtered (``False``) or smoothed (``True``): measured
#: 56-150 ns filtered, 130-180 ns smoothed and 180-250 ns lag-one (2,000 runs x 2,000 samples, 50,000 x 200,
#: 500,000 x 20).
_RUN_STEP = {False: 15, True: 25}


def _kalman_work(steps: int, runs: int, smoothed: bool, names: str) -> int:
    """Refuse (rule 17, ``fusion._limits.loop_work``), naming ``names``, a Kalman filter of ``steps`` grid steps over
    ``runs`` runs (with the smoother's pass if ``smoothed``) before its loop: ``steps x (step + runs x _RUN_STEP)``
    units, the step ``_KALMAN_STEP`` or ``_SMOOTHER_STEP`` (fuzz 53b C4). The edge of one run, 331,674 filter
    steps or 248,447 lag-one ones, ran 11.6 and 11.1 CPU-s (the machine loaded, load average 7 on 2 cores)."""
    return loop_work((int(steps),), int(runs) * _RUN_STEP[bool(smoothed)], names,
                     step=_SMOOTHER_STEP if smoothed else _KALMAN_STEP)


def kalman_filter(
    t: ArrayLike, z: ArrayLike, sigma: float, q_v: float = 1e-2, q_a: float = 1e-3, *,
    q_model: str = "per-step", init: str = "source", p0: tuple[float, float] = (100.0, 100.0),
    t_extra: ArrayLike | None = None, period: float = 2.0,
) -> FilteredStates:
    r"""Constant-acceleration Kalman filter of Shi, Suo & Ma (2023), eqs. (1)-(6) (rebuilt), via filterpy.

    State :math:`[x, \dot x, \ddot x]`, transition :math:`\Phi(T_n)` (:func:`ca_transition`),
    driving noise :func:`process_noise` (default: the text's per-step
    :math:`Q = \mathrm{diag}(0, q_v, q_a)`, which is *not* a Bar-Shalom model),
    :math:`H = [1, 0, 0]`, :math:`C = \sigma^2`. Initial state :math:`[z_1, 0, 0]`, covariance
    :math:`\mathrm{diag}(\sigma^2, p_{0,v}, p_{0,a})` (the source says only "from experience").
    With ``init="source"`` the filter then also updates with :math:`z_1`, so the first
    measurement is used twice (our implementation choice; the text says nothing about it);
    ``init="once"`` starts from that prior
    at :math:`t_1` without the second update. ``t_extra`` inserts prediction-only steps (the
    source's change of the filter period at registration instants): with the per-step
    :math:`Q` they add driving noise, with the white-noise-jerk :math:`Q(T)` they change nothing.

    This is the reference implementation; :func:`kalman_runs` is the same filter vectorised over
    runs (tested equal).

    Parameters
    ----------
    t, z : array_like, shape (n,)
        Sample times (s) and position measurements (m).
    sigma : float
        Measurement-noise standard deviation (m), > 0.
    q_v, q_a : float
        Driving-noise variances (m²/s², m²/s⁴), >= 0 (see :func:`process_noise`).
    q_model : str
        One of :data:`Q_MODELS`.
    init : str
        One of :data:`INITS`.
    p0 : tuple of float
        Initial velocity and acceleration variances, > 0.
    t_extra : array_like, optional
        Prediction-only instants (s) inserted between the samples.
    period : float
        Nominal period calibrating the white-noise-jerk density (s).

    Returns
    -------
    FilteredStates
        ``x`` (n, 3) and ``P`` (n, 3, 3) at the sample times.

    Raises
    ------
    ValueError
        Times not finite or not strictly increasing, ``sigma`` not positive, ``q_v`` or ``q_a``
        negative or not finite, unknown ``q_model`` or ``init``, bad ``p0``; more grid steps (samples and instants
        of ``t_extra``) than the work budget (``fusion._limits.MAX_WORK``: 331,674, about 10 CPU-s), naming ``t`` and
        ``z``, before the loop.

    Notes
    -----
    Accuracy: as :func:`fusion.filtering.kalman.gain_sequence`'s, the covariance recursion loses precision when
    ``p0`` is far above the posterior (fuzz 46b D1: p0 = 1e12 against 1e13 moves the acceleration estimate by 3e-4
    relative, 1e16 against 1e17 by 0.5 %); p0 up to about 1e10 times ``sigma**2`` is accurate to ~1e-6 (measured
    against an exact rational recursion: 5e-6 at p0 = 1e10, sigma = 1).

    References
    ----------
    * Kalman, R. E. (1960). A new approach to linear filtering and prediction problems.
      *Journal of Basic Engineering*, 82(1), 35-45.
    * Bar-Shalom, Y., Li, X. R., & Kirubarajan, T. (2001). *Estimation with Applications to
      Tracking and Navigation*. Wiley.
    """
    tt, zz = _series(t, z, 1)
    sigma, q_v, q_a, q_model, init, p0, period = _kf_options(sigma, q_v, q_a, q_model, init, p0, period)
    names = "t and z" if t_extra is None else "t, z and t_extra"
    _kalman_work(tt.size, 1, False, names)  # rule 17: the samples alone, before the grid's sort
    g, is_sample = _grid(tt, t_extra)
    _kalman_work(g.size, 1, False, names)  # and the grid's steps, before the loop
    kf = KalmanFilter(dim_x=3, dim_z=1)
    kf.x = np.array([zz[0], 0.0, 0.0])
    kf.P = np.diag([sigma**2, p0[0], p0[1]])
    kf.H = np.array([[1.0, 0.0, 0.0]])
    kf.R = np.array([[sigma**2]])
    xs = np.empty((tt.size, 3))
    Ps = np.empty((tt.size, 3, 3))
    if init == "source":
        kf.update(zz[0])
    xs[0], Ps[0] = kf.x, kf.P
    i = 1
    for m in range(1, g.size):
        dt = g[m] - g[m - 1]
        kf.predict(F=ca_transition(dt), Q=process_noise(dt, q_v, q_a, q_model, period))
        if is_sample[m]:
            kf.update(zz[i])
            xs[i], Ps[i] = kf.x, kf.P
            i += 1
    _positive_variances(Ps, sigma, q_v, q_a, p0)
    return FilteredStates(x=xs, P=Ps)


def kalman_runs(
    t: ArrayLike, Z: ArrayLike, sigma: float, q_v: float = 1e-2, q_a: float = 1e-3, *,
    q_model: str = "per-step", init: str = "source", p0: tuple[float, float] = (100.0, 100.0),
    t_extra: ArrayLike | None = None, period: float = 2.0, smooth: bool = False, lag_one: bool = False,
) -> FilteredStates:
    r""":func:`kalman_filter` vectorised over runs, optionally followed by the RTS smoother.

    The covariances and gains do not depend on the data, so they are computed once and every
    run's state is updated with the same gain. With ``smooth=True`` the Rauch-Tung-Striebel
    fixed-interval smoother runs backwards over the whole grid (samples and ``t_extra``):
    :math:`\hat{\mathbf x}^s_m = \hat{\mathbf x}_m + C_m(\hat{\mathbf x}^s_{m+1} - \Phi_m\hat{\mathbf x}_m)`,
    :math:`C_m = P_m\Phi_m^\top (P^-_{m+1})^{-1}` (uses every sample: offline).

    Parameters
    ----------
    t : array_like, shape (n,)
        Sample times (s).
    Z : array_like, shape (n,) or (runs, n)
        Measurements (m), one row per run.
    sigma, q_v, q_a, q_model, init, p0, t_extra, period
        As in :func:`kalman_filter`.
    smooth : bool
        Return RTS-smoothed states (and covariances) instead of filtered ones.
    lag_one : bool
        Return fixed-lag smoothed states with a lag of one grid step instead:
        :math:`E[\mathbf x_m \mid z_1, \dots, z_{m+1}]`, one RTS step back from the *filtered* state
        :math:`\hat{\mathbf x}_{m+1}` (the last state stays filtered). It uses exactly the information of
        an interpolation that waits for the next sample. Exclusive with ``smooth``.

    Returns
    -------
    FilteredStates
        ``x`` of shape (n, 3) or (runs, n, 3), ``P`` of shape (n, 3, 3).

    Raises
    ------
    ValueError
        As :func:`kalman_filter` (the work budget counting each run of ``Z`` at each grid step, and the smoother's
        pass: 248,447 smoothed steps of one run); ``Z`` whose last axis does not match ``t``; ``smooth`` and
        ``lag_one`` both set; with ``smooth`` or ``lag_one``, a
        predicted covariance singular to working precision (``sigma``, ``q_v`` and ``q_a`` named: no process noise
        and a measurement variance far below ``p0``, fuzz 49b D1).

    Notes
    -----
    Accuracy: as :func:`kalman_filter`'s; without process noise (``q_v = q_a = 0``) the posterior is the measurement
    variance's scale and the error grows with ``p0 / sigma**2`` (fuzz 49b D1, against an exact rational batch
    solution of the smoother of chapter 07's default flight, ``p0`` = 100: relative error of the expected MSE 2e-9 at
    sigma = 0.01 m, 1e-6 at 1e-4 m, 31 % at 1e-6 m; from about 3e-7 m the predicted covariance is singular and the
    smoothers refuse).

    References
    ----------
    * Rauch, H. E., Tung, F., & Striebel, C. T. (1965). Maximum likelihood estimates of linear
      dynamic systems. *AIAA Journal*, 3(8), 1445-1450.
    """
    flag(smooth, "smooth")
    flag(lag_one, "lag_one")
    if smooth and lag_one:  # before any work (it was checked after the filter's loop)
        raise ValueError("smooth and lag_one cannot both be set")
    zarr = _numeric(Z, "Z")
    one = zarr.ndim == 1
    zz2 = np.atleast_2d(zarr)
    if zz2.ndim != 2 or zz2.size == 0:
        raise ValueError(f"Z must be a non-empty 1-D or 2-D array, got shape {zarr.shape}")
    check_magnitude(zz2, "Z")
    tt = _numeric(t, "t")
    if tt.ndim != 1 or zz2.shape[1] != tt.size:
        raise ValueError(f"Z must have one column per sample time t ({tt.shape}), got shape {zarr.shape}")
    tt, _ = _series(tt, zz2[0], 1)
    sigma, q_v, q_a, q_model, init, p0, period = _kf_options(sigma, q_v, q_a, q_model, init, p0, period)
    names = "t and Z" if t_extra is None else "t, Z and t_extra"
    smoothed = bool(smooth or lag_one)
    _kalman_work(tt.size, zz2.shape[0], smoothed, names)  # rule 17: the samples alone, before the grid's sort
    g, is_sample = _grid(tt, t_extra)
    _kalman_work(g.size, zz2.shape[0], smoothed, names)  # and the grid's steps, before the loops
    M, R = g.size, zz2.shape[0]
    r2 = sigma**2
    X = np.empty((R, M, 3))
    P = np.empty((M, 3, 3))
    Pp = np.empty((M, 3, 3))
    F = np.empty((M, 3, 3))
    x = np.zeros((R, 3))
    x[:, 0] = zz2[:, 0]
    Pm = np.diag([r2, p0[0], p0[1]])

    def update(x: FloatArray, Pm: FloatArray, zcol: FloatArray) -> tuple[FloatArray, FloatArray]:
        k = Pm[:, 0] / (Pm[0, 0] + r2)
        x = x + np.outer(zcol - x[:, 0], k)
        ikh = np.eye(3) - np.outer(k, [1.0, 0.0, 0.0])
        Pm = ikh @ Pm @ ikh.T + r2 * np.outer(k, k)  # Joseph form, as filterpy
        return x, Pm

    if init == "source":
        x, Pm = update(x, Pm, zz2[:, 0])
    X[:, 0], P[0], Pp[0], F[0] = x, Pm, Pm, np.eye(3)
    i = 1
    for m in range(1, M):
        dt = g[m] - g[m - 1]
        F[m] = ca_transition(dt)
        x = x @ F[m].T
        Pm = F[m] @ Pm @ F[m].T + process_noise(dt, q_v, q_a, q_model, period)
        Pp[m] = Pm
        if is_sample[m]:
            x, Pm = update(x, Pm, zz2[:, i])
            i += 1
        X[:, m], P[m] = x, Pm
    if lag_one:
        Xf, Pf = X.copy(), P.copy()
        for m in range(M - 1):
            C = _smoother_gain(Pp[m + 1], Pf[m] @ F[m + 1].T, g[m + 1], sigma, q_v, q_a, p0)
            X[:, m] = Xf[:, m] + (Xf[:, m + 1] - Xf[:, m] @ F[m + 1].T) @ C.T
            P[m] = Pf[m] + C @ (Pf[m + 1] - Pp[m + 1]) @ C.T
    if smooth:
        for m in range(M - 2, -1, -1):
            C = _smoother_gain(Pp[m + 1], P[m] @ F[m + 1].T, g[m + 1], sigma, q_v, q_a, p0)
            X[:, m] = X[:, m] + (X[:, m + 1] - X[:, m] @ F[m + 1].T) @ C.T
            P[m] = P[m] + C @ (P[m + 1] - Pp[m + 1]) @ C.T
    xs, Ps = X[:, is_sample], P[is_sample]
    _positive_variances(Ps, sigma, q_v, q_a, p0)
    return FilteredStates(x=xs[0] if one else xs, P=Ps)


def _positive_variances(Ps: FloatArray, sigma: float, q_v: float, q_a: float, p0: tuple[float, float]) -> None:
    """Refuse, naming ``sigma``, ``q_v``, ``q_a`` and ``p0``, covariances with a variance that is not positive (or
    not finite): every variance of the exact recursion is positive (``p0`` and ``sigma`` are), so such a one is the
    recursion's round-off, and certainly wrong (fuzz 51 C2: sigma = 3e-6 m, p0 = (2.8e7, 0.02) returned a variance of
    -9.6e-11 for the exact 6.2e-11). A covariance with positive variances may still be inaccurate (see Notes)."""
    d = np.diagonal(Ps, axis1=-2, axis2=-1)
    if not (d > 0).all():
        raise ValueError(f"sigma = {shown(sigma)} m, q_v = {shown(q_v)}, q_a = {shown(q_a)} and p0 = {shown(p0)} "
                         "leave the filter's covariance recursion with a variance that is not positive (round-off: "
                         "the prior far above the posterior; see Notes): its results would be wrong")


def _smoother_gain(Pp: FloatArray, PF: FloatArray, t: float, sigma: float, q_v: float, q_a: float,
                   p0: tuple[float, float]) -> FloatArray:
    r"""The smoother's gain :math:`C = P\Phi^\top (P^-)^{-1}` (``PF`` is :math:`P\Phi^\top`, ``Pp`` the predicted
    covariance at ``t``), refused naming ``sigma``, ``q_v``, ``q_a`` and ``p0`` where ``Pp`` is singular to working precision
    (fuzz 49b D1: sigma = 1e-8 m with q_v = q_a = 0 raised LinAlgError, reported under the internal names of
    ``fusion.registration.analysis.expected_mse``)."""
    try:
        C = np.linalg.solve(Pp.T, PF.T).T
    except np.linalg.LinAlgError:
        C = None
    if C is None or not np.isfinite(C).all():
        raise ValueError(
            f"sigma = {shown(sigma)} m with q_v = {shown(q_v)}, q_a = {shown(q_a)} and p0 = {shown(p0)} leave the "
            f"smoother's predicted covariance singular to working precision at t = {t:g} s: with no process noise (or "
            f"this little) the covariance collapses to the scale of the measurement variance sigma**2, "
            f"{max(p0) / sigma**2:.1e} times below the prior p0, beyond the precision of the covariance recursion (see "
            "Notes); give q_v or q_a > 0, a larger sigma or a smaller p0")
    return C


@derived_inputs()
def kalman_register(
    t: ArrayLike, z: ArrayLike, t_query: ArrayLike, sigma: float, q_v: float = 1e-2, q_a: float = 1e-3
) -> FloatArray:
    r"""Kalman-filter registration of Shi, Suo & Ma (2023), §3: predict the last estimate to the instant.

    The filter runs at the sampling period; for an instant :math:`t_k` it changes the period
    to :math:`t_k - t_i`, with :math:`t_i` the last sample not later than :math:`t_k`, and
    reports :math:`H\Phi(t_k - t_i)\hat{\mathbf x}_i`. (Instants before the first sample are
    predicted backwards from it.)

    Parameters
    ----------
    t, z : array_like, shape (n,)
        Sample times (s, strictly increasing) and position measurements (m) of the fast sensor.
    t_query : array_like, shape (K,)
        Registration instants (s).
    sigma : float
        Measurement-noise standard deviation (m), > 0.
    q_v, q_a : float
        Per-step variances of the velocity and acceleration disturbances, >= 0
        (see :func:`kalman_filter`).

    Returns
    -------
    ndarray, shape (K,)
        Registered positions (m).

    Raises
    ------
    ValueError
        Times not finite or not strictly increasing, too few samples, ``sigma`` not positive,
        ``q_v`` or ``q_a`` negative; more samples than :func:`kalman_filter`'s work budget (331,674), naming ``t``
        and ``z``.

    References
    ----------
    * Kalman, R. E. (1960). A new approach to linear filtering and prediction problems.
      *Journal of Basic Engineering*, 82(1), 35-45.
    * Bar-Shalom, Y., Li, X. R., & Kirubarajan, T. (2001). *Estimation with Applications to
      Tracking and Navigation*. Wiley.
    """
    tt, zz = _series(t, z, 1)
    xs = kalman_filter(tt, zz, sigma, q_v, q_a).x
    return predict_to(tt, xs, t_query)


def predict_to(t: ArrayLike, states: ArrayLike, t_query: ArrayLike) -> FloatArray:
    r"""Predict filtered constant-acceleration states to the query instants (Shi, Suo & Ma (2023), §3).

    For each instant :math:`t_k` take the last state time :math:`t_i \le t_k` and return
    :math:`H\Phi(t_k - t_i)\hat{\mathbf x}_i = \hat x_i + \Delta\hat{\dot x}_i + \tfrac12\Delta^2\hat{\ddot x}_i`,
    :math:`\Delta = t_k - t_i` (instants before the first state are predicted backwards).

    Parameters
    ----------
    t : array_like, shape (n,)
        Strictly increasing times of the states (s).
    states : array_like, shape (n, 3)
        Filtered states :math:`[x, \dot x, \ddot x]` (m, m/s, m/s²), e.g. from :func:`kalman_filter`.
    t_query : array_like, shape (K,)
        Registration instants (s).

    Returns
    -------
    ndarray, shape (K,)
        Predicted positions (m).
    """
    xs = _numeric(states, "states")
    tt = _numeric(t, "t")
    if xs.ndim != 2 or xs.shape[1] != 3 or tt.shape != (xs.shape[0],):
        raise ValueError(f"states must have shape (n, 3) matching t of shape (n,), got {xs.shape} and {tt.shape}")
    as_array(xs, "states")
    _series(tt, xs[:, 0], 1)
    q = _query(t_query)
    i = np.clip(np.searchsorted(tt, q, side="right") - 1, 0, tt.size - 1)
    dt = q - tt[i]
    return xs[i, 0] + dt * xs[i, 1] + 0.5 * dt**2 * xs[i, 2]


def improved_register(
    t: ArrayLike, z: ArrayLike, t_query: ArrayLike, sigma: float, q_v: float = 1e-2, q_a: float = 1e-3,
    causal: bool = False,
) -> FloatArray:
    """The proposal of Shi, Suo & Ma (2023), §4: Kalman-filter the samples, then :func:`three_point`.

    The filtered positions :math:`\\hat x_i` (:func:`kalman_filter`) replace the raw samples in
    the three-point Lagrange interpolation (at least three samples are needed).
    With ``causal=True`` the three filtered positions are the last three not later than the
    instant (a real-time variant the source does not describe).

    Parameters
    ----------
    t, z : array_like, shape (n,)
        Sample times (s, strictly increasing) and position measurements (m) of the fast sensor.
    t_query : array_like, shape (K,)
        Registration instants (s).
    sigma : float
        Measurement-noise standard deviation (m), > 0.
    q_v, q_a : float
        Per-step variances of the velocity and acceleration disturbances, >= 0
        (see :func:`kalman_filter`).
    causal : bool
        Use only filtered positions not later than each instant.

    Returns
    -------
    ndarray, shape (K,)
        Registered positions (m).

    Raises
    ------
    ValueError
        Times not finite or not strictly increasing, too few samples, ``sigma`` not positive,
        ``q_v`` or ``q_a`` negative; more samples than :func:`kalman_filter`'s work budget (331,674), naming ``t``
        and ``z``.
    """
    flag(causal, "causal")
    tt, zz = _series(t, z, 3)
    xs = kalman_filter(tt, zz, sigma, q_v, q_a).x
    return three_point(tt, xs[:, 0], t_query, causal=causal)


def quadratic_ls(t: ArrayLike, z: ArrayLike, t_query: ArrayLike, lookahead: int = 1,
                 past: int | None = None) -> FloatArray:
    r"""Quadratic least-squares fit through the samples up to ``lookahead`` samples after the instant.

    For an instant :math:`t_k` with :math:`t_j \le t_k < t_{j+1}`, fit
    :math:`\alpha + \beta(s - t_k) + \gamma(s - t_k)^2` by least squares to the samples
    :math:`t_1, \dots, t_{j+\text{lookahead}}` and return :math:`\alpha`. With ``lookahead=1`` it
    uses exactly the information of the improved method of Shi, Suo & Ma (2023) (the whole past
    and the next sample); ``lookahead=0`` is causal. With ``past`` set the fit is local (a sliding
    window): only the last ``past`` samples not later than the instant, :math:`t_{j-\text{past}+1}, \dots,
    t_{j+\text{lookahead}}`. At least three samples are always used (the first three before :math:`t_3`).

    Parameters
    ----------
    t, z : array_like, shape (n,), n >= 3
        Strictly increasing sample times (s) and samples (m).
    t_query : array_like, shape (K,)
        Registration instants (s).
    lookahead : int
        Number of samples after the instant that the fit may use, >= 0.
    past : int, optional
        Number of samples not later than the instant that the fit uses (a local fit), >= 1;
        default every past sample (a growing-memory, global fit).

    Returns
    -------
    ndarray, shape (K,)
        Registered values (m).

    Raises
    ------
    ValueError
        Fewer than three samples, bad times, negative ``lookahead``, ``past`` below 1.

    References
    ----------
    * Blair, W. D., Rice, T. R., Alouani, A. T., & Xia, P. (1991). Asynchronous data fusion for
      target tracking with a multitasking radar and optical sensor. In *Acquisition, Tracking, and
      Pointing V*, Proceedings of SPIE, 1482.
    """
    tt, zz = _series(t, z, 3)
    q = _query(t_query)
    lookahead = count(lookahead, "lookahead", minimum=0)
    if past is not None:
        past = count(past, "past", minimum=1)
    last = np.clip(np.searchsorted(tt, q, side="right") - 1 + int(lookahead), 2, tt.size - 1)
    first = np.zeros(q.size, dtype=int) if past is None else np.clip(last - int(lookahead) - int(past) + 1, 0, None)
    first = np.minimum(first, last - 2)
    # rule 17: a least-squares fit per query (~10 loop steps of numpy calls) over its window of samples
    loop_work((q.size,), 3 * int(np.max(last - first + 1)), "t_query and t", step=10 * LOOP_STEP)
    out = np.empty(q.size)
    for k, tk in enumerate(q):
        s = tt[first[k]: last[k] + 1] - tk
        W = np.column_stack([np.ones(s.size), s, s * s])
        coef, *_ = np.linalg.lstsq(W, zz[first[k]: last[k] + 1], rcond=None)
        out[k] = coef[0]
    return out


@finite_result("t, z and t_query")
def spline_register(t: ArrayLike, z: ArrayLike, t_query: ArrayLike) -> FloatArray:
    r"""Cubic-spline interpolation through every sample (``scipy.interpolate.CubicSpline``, not-a-knot).

    Offline: the spline's value between two samples depends on every sample of the record.
    It reproduces any cubic, hence the quadratic trajectory of Shi, Suo & Ma (2023), exactly.

    Parameters
    ----------
    t, z : array_like, shape (n,), n >= 4
        Strictly increasing sample times (s) and samples (m).
    t_query : array_like, shape (K,)
        Registration instants (s).

    Returns
    -------
    ndarray, shape (K,)
        Registered values (m).

    Raises
    ------
    ValueError
        Fewer than four samples or bad times.

    References
    ----------
    * de Boor, C. (1978). *A Practical Guide to Splines*. Springer.
    """
    tt, zz = _series(t, z, 4)
    q = _query(t_query)
    return np.asarray(CubicSpline(tt, zz, bc_type="not-a-knot")(q), dtype=float)
