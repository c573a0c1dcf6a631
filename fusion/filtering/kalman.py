r"""Linear Kalman filtering vectorised over Monte-Carlo runs.

Used by the two-sensor case of Wang & Tang (2024). State :math:`\mathbf x = [x, \dot x, y, \dot y]^\top` (m, m/s), constant-velocity model

.. math:: F = \begin{bmatrix}1&T&0&0\\0&1&0&0\\0&0&1&T\\0&0&0&1\end{bmatrix},\qquad
          H = \begin{bmatrix}1&0&0&0\\0&0&1&0\end{bmatrix},

process noise :math:`Q` on the full state as printed, measurement noise
:math:`R_j = \mathrm{diag}(\Delta_j^2, \Delta_j^2)`.

A Kalman filter's gains and covariances do not depend on the measurements, so they are
computed once (filterpy's recursion, operation for operation: bit-for-bit its gains and
covariances) and every run is then propagated at once with numpy. The same holds for every
fusion rule here (their weights depend on covariances only).

References
----------
* Kalman, R. E. (1960). A new approach to linear filtering and prediction problems.
  *Journal of Basic Engineering*, 82(1), 35-45.
* Bar-Shalom, Y., Li, X. R., & Kirubarajan, T. (2001). *Estimation with Applications to
  Tracking and Navigation*. Wiley.
* Labbe, R. (2014-). FilterPy: Kalman filters and other optimal and non-optimal estimation
  filters in Python. Software library.
"""

from __future__ import annotations

import math
from dataclasses import dataclass

import numpy as np
from numpy.typing import ArrayLike

from fusion._counts import allocation
from fusion._covariances import asymmetric
from fusion._limits import LOOP_STEP, loop_work, work
from fusion._results import ResultSpec, array, trusted, validated_post_init
from fusion._frozen import frozen_arrays
from fusion._validation import (_covariance_magnitude, _given_shape, _numeric, FloatArray, as_array, as_covariance,
                                as_semidefinite, count, input_size, finite_result, instance_of, one_of, positive_scalar)

__all__ = [
    "SplitCovariances",
    "CvModel",
    "cv_model",
    "GainSequence",
    "gain_sequence",
    "split_covariances",
    "filter_runs",
    "ErrorMoments",
    "error_moments",
    "rmse_per_step",
    "nees",
]

try:  # the kernel of numpy.linalg.inv without its per-call wrapper (the same LAPACK routine, the same bits)
    from numpy.linalg._umath_linalg import inv as _inv_kernel
except ImportError:  # pragma: no cover - another numpy layout: the public function
    _inv_kernel = None


def _inv(a: FloatArray) -> FloatArray:
    """``numpy.linalg.inv`` of a float64 (m, m) matrix: bit-for-bit its result, without its 3 µs wrapper.

    Only for matrices known to be invertible (an innovation covariance ``HPH' + R`` with ``R``
    positive definite): the public function's singularity check is not repeated.
    """
    if _inv_kernel is None:  # pragma: no cover
        return np.linalg.inv(a)
    return _inv_kernel(a, signature="d->d")


@dataclass(frozen=True)
@frozen_arrays
class CvModel:
    """Constant-velocity model matrices: transition and position measurement.

    Arrays are read-only.

    Attributes
    ----------
    F : ndarray, shape (4, 4)
        State transition.
    H : ndarray, shape (2, 4)
        Position measurement matrix.
    """

    F: FloatArray
    H: FloatArray


def cv_model(T: float) -> CvModel:
    """Constant-velocity ``F`` (4x4) and position-measurement ``H`` (2x4) for period ``T`` (s).

    State ordering :math:`[x, \\dot x, y, \\dot y]` (m, m/s); see the module docstring for the
    matrices (Wang & Tang (2024), §3.2; Bar-Shalom, Li & Kirubarajan 2001).

    Parameters
    ----------
    T : float
        Sampling period in seconds, > 0.

    Returns
    -------
    CvModel
        ``F`` and ``H``.

    Raises
    ------
    ValueError
        ``T`` not positive or not finite.
    """
    T = positive_scalar(T, "T")
    F = np.array([[1.0, T, 0.0, 0.0], [0.0, 1.0, 0.0, 0.0], [0.0, 0.0, 1.0, T], [0.0, 0.0, 0.0, 1.0]])
    H = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]])
    return CvModel(F=F, H=H)


@dataclass(frozen=True)
class GainSequence:
    """Kalman gains and covariances of one filter, independent of the data.

    Arrays are read-only. Built with ``dataclasses.replace`` or directly, every field is checked
    (``fusion._results``): finite, shapes consistent (``K`` steps, state dimension ``n``,
    ``m`` measurements), ``P`` symmetric positive semidefinite; otherwise a :class:`ValueError`
    naming the field (``GainSequence.H: ...``).

    Attributes
    ----------
    K : ndarray, shape (K, n, m)
        Gains at steps 1..K-1 (``K[0]`` is unused: step 0 is the initialisation).
    P : ndarray, shape (K, n, n)
        Filtered covariances.
    F : ndarray, shape (n, n)
        State transition.
    H : ndarray, shape (m, n)
        Measurement matrix.
    """

    K: FloatArray
    P: FloatArray
    F: FloatArray
    H: FloatArray

    __result_spec__ = ResultSpec({"K": array("K", "n", "m"), "P": array("K", "n", "n", covariance=True),
                                  "F": array("n", "n"), "H": array("m", "n")})
    __post_init__ = validated_post_init


def _model(F: ArrayLike, H: ArrayLike) -> tuple[FloatArray, FloatArray]:
    """A finite square transition ``F`` (n, n) and a finite measurement matrix ``H`` (m, n)."""
    F = as_array(F, "F", ndim=2)
    if F.shape[0] != F.shape[1]:
        raise ValueError(f"F must be square, got shape {F.shape}")
    H = as_array(H, "H", ndim=2)
    if H.shape[1] != F.shape[0]:
        raise ValueError(f"H must have {F.shape[0]} columns to match F, got shape {H.shape}")
    return F, H


def _steps_allocation(steps: int, n: int, per_state: int, names: str) -> None:
    """Rule 9 for a filter's per-step arrays (fuzz 36a C1): ``steps`` x ``n`` x ``per_state`` float64 (gains and
    covariances of an ``n``-state model at every step, and the estimates of every run), refused by ``names`` (the
    caller's arguments that set the steps and the state size) before any of them is built."""
    allocation((steps, n, per_state), names)


#: The weights of a filter loop's steps (``_steps_work``), in units (about 10 ns, ``fusion._limits.MAX_WORK``),
#: re-measured by fuzz 39a C1 (the earlier weights charged each run's ``n x max(n, m)`` products a whole unit, where
#: the batched BLAS products cost 0.03-0.5 ns each at larger n: valid calls of 0.2-2 CPU-s were refused, e.g.
#: ``local_track`` with n = 40, 1,500 runs and 420 steps). Measured with ``time.process_time`` and
#: ``OPENBLAS_NUM_THREADS=1`` (the machine shared with other jobs, the least of three) over n = 2 to 300, m = n / 2,
#: ``m = n``, ``m = 300`` with n = 4 and 30, runs 1 to 10,000, each function's CPU time a step fitted (non-negative least
#: squares of the relative error) as ``step + matrix x n(n + 2m) + cube x n**3 + m_cube x m**3 + runs x (run x (n + m)
#: + product x n(n + 2m))``: the ``n x n``, ``m x n`` and ``n x m`` matrices read once a step, the dense ``n x n`` and
#: ``m x m`` products and inverses, each run's state and measurement entries and its products with the matrices
#: (``fuse_tracks``: ``m = 0``). With the weights below the accepted edge of every measured (n, m, runs) ran 6-18
#: CPU-s (fusion_loop's split rules 22 s at 10,000 runs of n = 4; fuzzy clustering 4-20 s).
#:
#: :func:`filter_runs`: 2.5-3 us a step, 0.04-0.6 ns a ``n(n + 2m)`` of the matrices, 4-6 ns a run's entry and 0.03
#: ns its product (250 units, 0.025, 0.5 and 0.003); on its path of independent axes 0.47 us a run and step (50 units).
FILTER_RUNS_STEP = LOOP_STEP // 4
FILTER_RUNS_MATRIX = 0.025
FILTER_RUNS_RUN = 0.5
FILTER_RUNS_PRODUCT = 0.003
FILTER_RUNS_AXES_RUN = LOOP_STEP // 20
#: :func:`fusion.filtering.tracks.local_track` (its ``gain_sequence``, ``split_covariances`` and ``filter_runs``):
#: 23-31 us a step at n <= 10 (2 LOOP_STEP, plus the ``R`` given per step: at least its ``split_covariances``' step, so
#: that its own budget, naming z, refuses first), 20 ns a ``n(n + 2m)``, 0.6 ns a ``n**3``, 0.12 ns a ``m**3``, 8 ns
#: a run's entry and 0.01 ns a product.
LOCAL_TRACK_STEP = 2 * LOOP_STEP
LOCAL_TRACK_MATRIX = 2.0
LOCAL_TRACK_CUBE = 0.06
LOCAL_TRACK_M_CUBE = 0.012
LOCAL_TRACK_RUN = 0.8
LOCAL_TRACK_PRODUCT = 0.001
#: :func:`fusion.filtering.feedback.fusion_loop`: 170-550 us a step at n <= 10 (30 LOOP_STEP; its split rules,
#: whose weights are searched, 440-950 us: 60), 0.2 us a ``n(n + 2m)`` (0.25 us; 0.4 us with ``"printed"``), 2 ns a
#: ``n**3`` (5 ns; 8 ns with ``"printed"``, 1.3-1.5 times ``"split"`` at n = 40 to 300), 0.1 ns a ``m**3`` (0.2 ns),
#: 15 ns a run's entry and 0.13 ns a product (both filters and the fusion).
FUSION_LOOP_STEP = 30 * LOOP_STEP
FUSION_LOOP_SPLIT_STEP = 60 * LOOP_STEP
#: ``"printed"`` with feedback (``"split"`` or ``"common"``): 1.2-1.5 ms a step measured (fix 72f: K = 1,000 and 3,000,
#: n = 2, one run; the least of 3, the machine loaded, load average 10 on 2 cores), so the edge at 60 ran 20-25 CPU-s.
FUSION_LOOP_PRINTED_FEEDBACK_STEP = 150 * LOOP_STEP
FUSION_LOOP_MATRIX = 20.0
FUSION_LOOP_SPLIT_MATRIX = 25.0
FUSION_LOOP_PRINTED_MATRIX = 40.0
FUSION_LOOP_CUBE = 0.2
FUSION_LOOP_SPLIT_CUBE = 0.5
FUSION_LOOP_PRINTED_CUBE = 0.8
FUSION_LOOP_M_CUBE = 0.01
FUSION_LOOP_SPLIT_M_CUBE = 0.02
FUSION_LOOP_RUN = 1.5
FUSION_LOOP_PRODUCT = 0.013
#: :func:`fusion.filtering.tracks.fuse_tracks` (``m = 0``: the tracks' state only): 180-360 us a step at n <= 10
#: with ``"ci"`` and fuzzy clustering (25 LOOP_STEP), 110-140 us with ``"convex"`` (18), 200-320 us with ``"split"``
#: and ``"printed"`` (23), 0.35 us a ``n**2`` (0.25 us with ``"convex"``, 0.6 us with ``"split"`` and ``"printed"``),
#: a ``n**3`` 0.3 ns (0.6 ns with ``"split"``, 7 ns with ``"printed"``), 18 ns a run's entry; fuzzy clustering
#: iterates on every run: 0.2 us a ``n**2``, 0.2 ns a ``n**3``, 0.22 us a run's entry and 1.6 ns a run's ``n**2``.
FUSE_TRACKS_STEP = 25 * LOOP_STEP
FUSE_TRACKS_CONVEX_STEP = 18 * LOOP_STEP
FUSE_TRACKS_CONVEX_MATRIX = 25.0
FUSE_TRACKS_SPLIT_STEP = 23 * LOOP_STEP
FUSE_TRACKS_MATRIX = 35.0
FUSE_TRACKS_SPLIT_MATRIX = 60.0
FUSE_TRACKS_FUZZY_MATRIX = 20.0
FUSE_TRACKS_CUBE = 0.03
FUSE_TRACKS_SPLIT_CUBE = 0.06
FUSE_TRACKS_PRINTED_CUBE = 0.7
FUSE_TRACKS_FUZZY_CUBE = 0.02
FUSE_TRACKS_RUN = 1.8
#: The fewest entries a run's step of :func:`fusion.filtering.tracks.fuse_tracks`' linear rules is counted by (fuzz 41a
#: D1): a run's state at one step is one strided read and write whatever ``n`` below it, so at n = 1 and 2 a run's step
#: costs about what it does at n = 4: 25-27 ns at n = 1 and 41-80 ns at n = 2 measured with 30,000 runs of 1,000 steps,
#: 33-36 ns at n = 2 with 300,000 of 100 (``time.process_time``, the least of two calls, ``OPENBLAS_NUM_THREADS=1``,
#: machine shared), about 100 ns estimated by the fuzz at its edge of 1e6 runs of 275 steps (28-30 CPU-s); counted as
#: 4 entries, 72 ns, the edge of 1e6 runs at n <= 4 is 138 steps (about 5-14 CPU-s).
FUSE_TRACKS_RUN_ENTRIES = 4
FUSE_TRACKS_FUZZY_RUN = 22.0
FUSE_TRACKS_FUZZY_PRODUCT = 0.16
#: :func:`split_covariances` and :func:`error_moments` (one pass, no runs): 12-16 us a step (2 LOOP_STEP, 2 more for
#: each ``R`` given per step, checked per step), 3-15 ns a ``n(n + 2m)`` (1.5 and 0.3 units), 0.35 and 0.2 ns a
#: ``n**3`` (0.035 and 0.02), 5 and 2.5 ps a ``m**3`` (``K R K^T``, measured at n = 4 and 30, m = 300).
SPLIT_COVARIANCES_MATRIX = 1.5
SPLIT_COVARIANCES_CUBE = 0.035
SPLIT_COVARIANCES_M_CUBE = 0.0005
ERROR_MOMENTS_MATRIX = 0.3
ERROR_MOMENTS_CUBE = 0.02
ERROR_MOMENTS_M_CUBE = 0.00025
#: Units of one ``m**3`` of a :func:`gain_sequence` step, measured at n = 4 and 30, m = 150 and 300: 0.08-0.13 ns with
#: one ``R`` (0.02 units), 0.13-0.32 ns with one ``R`` per step, each checked (0.04).
GAINS_R_CUBE = 0.02
GAINS_STEP_R_CUBE = 0.04


def _steps_work(steps: int, runs: int, n: int, m: int, step: int, names: str, cube: float = 0.0,
                m_cube: float = 0.0, run: float = 0.0, product: float = 0.0, matrix: float = 0.0) -> None:
    """Rule 17 for a filter's loop over its steps (fuzz 36a C5, 37a C2, 39a C1): ``steps`` Python steps of ``step``
    units, each with ``matrix x n(n + 2m)`` units of reading its ``n x n``, ``m x n`` and ``n x m`` matrices,
    ``cube x n**3`` of dense ``n x n`` products and inverses, ``m_cube x m**3`` of ``m x m`` ones, and per run
    ``run x (n + m)`` units of its state and measurement entries and ``product x n(n + 2m)`` of its products with the
    matrices (the weights measured per function, the constants above), refused by ``names`` (the caller's arguments
    that set the steps and sizes) before the loop starts (:func:`fusion._limits.loop_work`)."""
    loop_work((steps,), _step_units(runs, n, m, cube, m_cube, run, product, matrix), names, step=step)


def _step_units(runs: int, n: int, m: int, cube: float = 0.0, m_cube: float = 0.0, run: float = 0.0,
                product: float = 0.0, matrix: float = 0.0) -> int:
    """The vectorised units of one step of ``_steps_work`` (without its ``step`` overhead), rounded up: a caller
    that runs several such loops sums them (fuzz 41a C2)."""
    products = n * (n + 2 * m)
    return math.ceil(matrix * products + cube * n ** 3 + m_cube * m ** 3 + runs * (run * (n + m) + product * products))


def _gains_work(n_steps: int, n: int, per_step_r: bool, names: str, m: int = 0) -> None:
    """Rule 17 for :func:`gain_sequence` (fuzz 36a D2): its worst case, a recursion that never reaches its fixed
    point (an unobserved state), one Python step of ``LOOP_STEP`` units (8 us measured, n = 4, m = 2), three with
    one ``R`` per step (26-28 us, each ``R`` checked), plus ``n**3 / 20`` units (0.3-0.9 ns an ``n**3`` at n = 30 and
    100) and :data:`GAINS_R_CUBE` (or :data:`GAINS_STEP_R_CUBE`) a ``m**3`` (the innovation covariance's inverse, and
    each ``R``'s check; fuzz 37a C2), refused by ``names`` (the caller's arguments) before any check of the steps'
    matrices (``fusion._limits.loop_work``)."""
    cube = n ** 3 // 20 + math.ceil((GAINS_STEP_R_CUBE if per_step_r else GAINS_R_CUBE) * m ** 3)
    loop_work((n_steps,), cube, names, step=(3 if per_step_r else 1) * LOOP_STEP)


def _per_step(R: ArrayLike, dim: int, n_steps: int, name: str, definite: bool = True) -> FloatArray:
    """``R`` as one (dim, dim) matrix per step, shape (n_steps, dim, dim): a constant matrix is repeated.

    Each matrix must be a valid covariance (positive definite if ``definite``, else semidefinite).
    """
    arr = _numeric(R, name)  # a ragged list or a masked array is refused by name, as everywhere
    if arr.ndim == 3:
        if arr.shape[0] != n_steps:
            raise ValueError(f"{name} must be ({dim}, {dim}) or one matrix per step ({n_steps}, {dim}, {dim}), "
                             f"got shape {arr.shape}")
        check = as_covariance if definite else as_semidefinite
        return np.stack([check(arr[k], dim=dim, name=f"{name}[{k}]") for k in range(n_steps)])
    one = as_covariance(arr, dim=dim, name=name) if definite else as_semidefinite(arr, dim=dim, name=name)
    return np.broadcast_to(one, (n_steps, dim, dim))


@finite_result("F, H, Q, R and P0")
def gain_sequence(F: ArrayLike, H: ArrayLike, Q: ArrayLike, R: ArrayLike, P0: ArrayLike, n_steps: int) -> GainSequence:
    """Run the covariance recursion of filterpy's :class:`~filterpy.kalman.KalmanFilter` once and record gains and P.

    The same operations as filterpy's ``predict`` and ``update`` on the same operands, so the gains and
    covariances are bit-for-bit filterpy's, at about a third of its cost per step (its state update and
    bookkeeping are left out); once the recursion reaches its floating-point fixed point with a constant
    ``R``, the remaining steps are copies of it (the same bits that computing them would give). A model of
    independent axes (``F`` of entries 0 and +-1, ``F``, ``Q``, ``P0`` block diagonal in 2 x 2 blocks, ``H``
    reading each block's first component, a constant diagonal ``R``: the constant-velocity model at
    ``T = 1``) runs one axis at a time on Python floats, with the same bits at a fifth of the cost.

    ``Q`` may be singular (positive semidefinite); ``R`` and ``P0`` must be positive definite.
    The recursion is :math:`P^- = FPF^\\top + Q`, :math:`K = P^-H^\\top(HP^-H^\\top + R_k)^{-1}`,
    :math:`P = (I - KH)P^-` (Kalman 1960). ``R`` may change from step to step (e.g. the
    covariance of a converted measurement, which depends on the geometry) as long as it does not
    depend on the data.

    Parameters
    ----------
    F : array_like, shape (n, n)
        State transition.
    H : array_like, shape (m, n)
        Measurement matrix.
    Q : array_like, shape (n, n)
        Process-noise covariance.
    R : array_like, shape (m, m) or (n_steps, m, m)
        Measurement-noise covariance: one for every step, or one per step (``R[0]`` is unused:
        step 0 is the initialisation).
    P0 : array_like, shape (n, n)
        Covariance of the initial estimate (step 0).
    n_steps : int
        Number of steps K, including step 0. The work budget counts the recursion's worst case, a model that
        never reaches its fixed point (about 10**6 steps of a 4-state model with one ``R``, 3 x 10**5 with one
        ``R`` per step), even for a model that would reach it and copy the remaining steps; a step of ``n``
        states and ``m`` measurements costs about ``n**3`` and ``m**3`` more (about 1,800 steps of 4 states and
        300 measurements).

    Returns
    -------
    GainSequence
        Gains and filtered covariances of steps 0..K-1.

    Raises
    ------
    ValueError
        ``Q`` not symmetric positive semidefinite, ``R`` (any step) or ``P0`` not symmetric positive
        definite, or of the wrong size; ``n_steps`` beyond the work budget.

    Notes
    -----
    Accuracy: the covariance form (Joseph's, as filterpy) loses precision when the prior is far above the
    posterior; its error relative to the result grows with that ratio (measured against an exact rational
    recursion, constant-velocity model, T = 1, R = I: relative error 4e-10 at P0 = 1e10 I, 8e-6 at P0/R = 1e12,
    7e-4 at 1e14, 21 % at 1e16; fuzz 46b D1). No refusal: the cheap first-order bound (machine epsilon times the
    largest ratio of a predicted variance to its update) over-refuses accurate calls by up to 1e4 (a precise
    measurement of a directly observed state is accurate in Joseph's form); :func:`fusion.filtering.tracks.local_track`
    checks its own split instead. Nor does a second recursion in information form (fix 57d; tried for
    :func:`fusion.registration.methods.kalman_runs` too and not kept: fuzz 51 C2, C3) separate accurate from
    inaccurate calls here:
    on a grid of 108 calls (constant-velocity model, T 0.1-10 s, P0 1e2-1e14 I, R I and 1e-4 I, q 0-1, 25 steps,
    against exact rational recursions) 12 of the 80 calls whose two forms agree within 1e-6 are off by more than
    1e-6 (up to 60 times the scale at P0/R = 1e18: both forms make the same error). Give a prior within about 1e10
    of the measurement noise.

    References
    ----------
    * Kalman, R. E. (1960). A new approach to linear filtering and prediction problems.
      *Journal of Basic Engineering*, 82(1), 35-45.
    * Bar-Shalom, Y., Li, X. R., & Kirubarajan, T. (2001). *Estimation with Applications to
      Tracking and Navigation*. Wiley.
    """
    F, H = _model(F, H)
    n, m = F.shape[0], H.shape[0]
    n_steps = count(n_steps, "n_steps")
    _steps_allocation(n_steps, n, n + m, "n_steps and the sizes of F and H")  # K (n_steps, n, m), P (n_steps, n, n)
    R = _numeric(R, "R")
    _gains_work(n_steps, n, R.ndim == 3, "n_steps, F and R", m)
    Q = as_semidefinite(Q, dim=n, name="Q")
    Rk = _per_step(R, m, n_steps, "R")
    P0 = as_covariance(P0, dim=n, name="P0")
    if Rk.strides[0] == 0 and _scalar_path_ok():  # one R for every step (broadcast)
        R = Rk[0]
        if _decoupled_axes(F, H, Q, P0) and np.array_equal(R, np.diag(np.diag(R))):  # independent axes
            Ks, Ps = _gains_axes(F, Q, R, P0, n_steps)
            return trusted(GainSequence, K=Ks, P=Ps, F=F.copy(), H=H.copy())
    Ks, Ps = _gains_matrices(F, H, Q, Rk, P0, n_steps)
    # computed from validated operands (a non-finite result is refused by finite_result): the private constructor
    return trusted(GainSequence, K=Ks, P=Ps, F=F.copy(), H=H.copy())


def _gains_matrices(F: FloatArray, H: FloatArray, Q: FloatArray, Rk: FloatArray, P0: FloatArray,
                    n_steps: int) -> tuple[FloatArray, FloatArray]:
    """The readable recursion of :func:`gain_sequence` (validated operands; ``Rk`` one matrix per step)."""
    n, m = F.shape[0], H.shape[0]
    Ks = np.zeros((n_steps, n, m))
    Ps = np.zeros((n_steps, n, n))
    Ps[0] = P0
    # filterpy's KalmanFilter.predict and .update (Joseph form), operation for operation on the same
    # operands, so every gain and covariance is bit-for-bit filterpy's (tested); only the state, which
    # the gains do not depend on, and filterpy's per-call bookkeeping are left out. Once P repeats
    # itself exactly (the Riccati recursion has reached its fixed point in floating point) and R no
    # longer changes, every later step would repeat the same operations on the same operands:
    # their results are copied instead of recomputed.
    dot, inv = np.dot, _inv
    eye, FT, HT = np.eye(n), F.T, H.T
    P = P0
    const_R = Rk.strides[0] == 0  # one R for every step (broadcast)
    for k in range(1, n_steps):
        R = Rk[k]
        P = dot(dot(F, P), FT) + Q  # predict: P = FPF' + Q (filterpy's fading factor is 1.0: exact)
        PHT = dot(P, HT)
        K = dot(PHT, inv(dot(H, PHT) + R), out=Ks[k])  # K = PH'(HPH' + R)^-1
        I_KH = eye - dot(K, H)
        P = np.add(dot(dot(I_KH, P), I_KH.T), dot(dot(K, R), K.T), out=Ps[k])  # Joseph form
        if k >= 2 and k % 4 == 0 and (P == Ps[k - 1]).all() and (const_R or (Rk[k + 1:] == R).all()):
            Ks[k + 1:], Ps[k + 1:] = K, P  # the fixed point: every later step gives these same bits
            break
    return Ks, Ps


@dataclass(frozen=True)
@frozen_arrays
class SplitCovariances:
    """Shared and independent parts of the local covariances at every step.

    Arrays are read-only.

    Attributes
    ----------
    Pd : ndarray, shape (K, 4, 4)
        Shared part at every step.
    Pi : ndarray, shape (K, 4, 4)
        Independent part at every step.
    """

    Pd: FloatArray
    Pi: FloatArray


def split_covariances(gains: GainSequence, Q: ArrayLike, R: ArrayLike, P0d: ArrayLike, P0i: ArrayLike,
                      R_shared: ArrayLike | None = None) -> SplitCovariances:
    r"""Split each filtered covariance into a process-noise part and a measurement part.

    With :math:`A = I - K H`: :math:`P_d^+ = A(F P_d F^\top + Q)A^\top + K R^{\rm sh} K^\top` (errors
    shared by every filter of the same target: process noise, common initial velocity, and any
    measurement noise another sensor's filter also sees) and :math:`P_i^+ = A F P_i F^\top A^\top +
    K R K^\top` (this sensor's own noise). Their sum is the filter's covariance (Joseph form), whose
    measurement noise is :math:`R + R^{\rm sh}`. This is the split that split covariance
    intersection needs (Wang & Tang (2024), eqs. 5-12).

    Parameters
    ----------
    gains : GainSequence
        Output of :func:`gain_sequence` (gains, F, H), run with measurement noise ``R + R_shared``.
    Q : array_like, shape (n, n)
        Process-noise covariance (goes to the shared part).
    R : array_like, shape (m, m) or (K, m, m)
        This sensor's own measurement-noise covariance (goes to the independent part), constant
        or one per step; positive definite, or positive semidefinite when ``R_shared`` is given.
    P0d, P0i : array_like, shape (n, n)
        Shared and independent parts of the initial covariance; they should sum to the ``P0``
        given to :func:`gain_sequence`.
    R_shared : array_like, shape (m, m) or (K, m, m), optional
        Measurement noise common to another sensor's filter (positive semidefinite; goes to the
        shared part). ``None``: none.

    Returns
    -------
    SplitCovariances
        ``Pd`` and ``Pi`` at every step.

    Raises
    ------
    ValueError
        Arrays of the wrong shape or not finite, covariances not valid; the steps of ``gains`` (with the sizes
        ``n`` and ``m``, and each ``R`` given per step) beyond the work budget (``fusion._limits.MAX_WORK``, ~10 CPU-s:
        about 5 x 10**5 steps of a 4-state model), named ``gains``.

    References
    ----------
    * Bar-Shalom, Y., & Campo, L. (1986). The effect of the common process noise on the
      two-sensor fused-track covariance. *IEEE Transactions on Aerospace and Electronic
      Systems*, AES-22(6), 803-805.
    """
    instance_of(gains, GainSequence, "gains")
    F, H = gains.F, gains.H
    n, m, K = F.shape[0], H.shape[0], gains.P.shape[0]
    # rule 17 (fuzz 37a C3): a Python step per step of gains, each R given per step checked per step
    R = _numeric(R, "R")
    R_shared = None if R_shared is None else _numeric(R_shared, "R_shared")
    per_step = (R.ndim == 3) + (R_shared is not None and R_shared.ndim == 3)
    _steps_work(K, 1, n, m, (2 + 2 * per_step) * LOOP_STEP, "gains (its steps K and sizes)",
                SPLIT_COVARIANCES_CUBE, SPLIT_COVARIANCES_M_CUBE, matrix=SPLIT_COVARIANCES_MATRIX)
    Q = as_semidefinite(Q, dim=n, name="Q")
    # with a shared part only the sum R + R_shared (checked by gain_sequence) must be definite
    Rk = _per_step(R, m, K, "R", definite=R_shared is None)
    Rs = np.zeros((K, m, m)) if R_shared is None else _per_step(R_shared, m, K, "R_shared", definite=False)
    Pd = np.zeros_like(gains.P)
    Pi = np.zeros_like(gains.P)
    Pd[0], Pi[0] = as_semidefinite(P0d, dim=n, name="P0d"), as_semidefinite(P0i, dim=n, name="P0i")
    for k in range(1, K):
        A = np.eye(n) - gains.K[k] @ H
        Pd[k] = A @ (F @ Pd[k - 1] @ F.T + Q) @ A.T + gains.K[k] @ Rs[k] @ gains.K[k].T
        Pi[k] = A @ F @ Pi[k - 1] @ F.T @ A.T + gains.K[k] @ Rk[k] @ gains.K[k].T
    return SplitCovariances(Pd=Pd, Pi=Pi)


def filter_runs(z: ArrayLike, gains: GainSequence, x0: ArrayLike) -> FloatArray:
    """Propagate the filter over every run at once.

    Parameters
    ----------
    z : array_like, shape (runs, K, m)
        Measurements.
    gains : GainSequence
        Precomputed gains (:func:`gain_sequence`).
    x0 : array_like, shape (runs, 4)
        Initial estimates (step 0).

    Returns
    -------
    ndarray, shape (runs, K, 4)
        Filtered estimates.

    Raises
    ------
    ValueError
        ``z`` or ``x0`` of the wrong shape or not finite; the steps of ``gains`` and the runs of ``z`` beyond the
        work budget (``fusion._limits.MAX_WORK``, ~10 CPU-s), named ``z and gains``.
    """
    instance_of(gains, GainSequence, "gains")
    K, n, m = gains.K.shape
    zz = as_array(z, "z", ndim=3)
    if zz.shape[1:] != (K, m):
        raise ValueError(f"z must be (runs, {K}, {m}) to match the gains, got {zz.shape}")
    _steps_allocation(K, zz.shape[0], n, "z and gains")  # the estimates (runs, K, n) of an n-state model
    # one or two runs of independent axes: a recursion per axis on Python floats (the same bits, tested)
    axes = zz.shape[0] <= _SCALAR_RUNS and _decoupled_axes(gains.F, gains.H) and _scalar_path_ok()
    if axes:  # gains across axes: zero for independent axes
        axes = not gains.K[:, np.kron(np.eye(m), np.ones((2, 1))) == 0].any()
    # rule 17 (fuzz 37a C3), each path weighed at its measured cost (fuzz 38a C7)
    if axes:
        _steps_work(K, 0, n, m, FILTER_RUNS_AXES_RUN * zz.shape[0], "z and gains (their steps K)")
    else:
        _steps_work(K, zz.shape[0], n, m, FILTER_RUNS_STEP, "z and gains (their steps K)", run=FILTER_RUNS_RUN,
                    product=FILTER_RUNS_PRODUCT, matrix=FILTER_RUNS_MATRIX)
    x = np.array(as_array(x0, "x0", ndim=2), dtype=float)
    if x.shape != (zz.shape[0], n):
        raise ValueError(f"x0 must be ({zz.shape[0]}, {n}) (one state per run of z), got {x.shape}")
    if axes:
        return _states_axes(zz, gains, x)
    return _states_matrices(zz, gains, x)


#: Up to this many runs, :func:`filter_runs` on a model of independent axes loops over runs in Python floats
#: (one run costs ~1 µs a step there, against ~3 µs a step for the array recursion whatever the runs).
_SCALAR_RUNS = 2


def _states_matrices(zz: FloatArray, gains: GainSequence, x: FloatArray) -> FloatArray:
    """The readable recursion of :func:`filter_runs` (validated operands), every run at once."""
    K = gains.K.shape[0]
    out = np.empty((zz.shape[0], K, gains.F.shape[0]))
    out[:, 0] = x
    # np.dot rather than @: the same BLAS product on these 2-D operands (the same bits, tested), at a
    # third of matmul's per-call overhead, which is what a run of one or a few filters costs
    dot, FT, HT, KT = np.dot, gains.F.T, gains.H.T, np.swapaxes(gains.K, 1, 2)
    for k in range(1, K):
        xp = dot(x, FT)
        x = xp + dot(zz[:, k] - dot(xp, HT), KT[k])
        out[:, k] = x
    return out


@dataclass(frozen=True)
@frozen_arrays
class ErrorMoments:
    r"""Mean and covariance of a fixed-gain filter's error on a known trajectory (:func:`error_moments`).

    Arrays are read-only.

    Attributes
    ----------
    mean : ndarray, shape (K, n)
        Expected error :math:`\mathrm E[\hat{\mathbf x}_k - \mathbf x_k]` (the lag, e.g. after a turn).
    cov : ndarray, shape (K, n, n)
        Covariance of the error from the measurement noise.
    """

    mean: FloatArray
    cov: FloatArray

    def rmse(self) -> FloatArray:
        r"""RMSE per step and component over infinitely many runs, :math:`\sqrt{b^2 + C_{ii}}`, shape (K, n)."""
        return np.sqrt(self.mean**2 + np.einsum("kii->ki", self.cov))


def error_moments(gains: GainSequence, truth: ArrayLike, R: ArrayLike, mean0: ArrayLike, cov0: ArrayLike) -> ErrorMoments:
    r"""Exact mean and covariance of the error of :func:`filter_runs` on a known, deterministic trajectory.

    With fixed gains :math:`K_k` and :math:`A_k = I - K_kH`, the estimate
    :math:`\hat{\mathbf x}_k = A_kF\hat{\mathbf x}_{k-1} + K_k\mathbf z_k` of
    :math:`\mathbf z_k = H\mathbf x_k + \mathbf v_k`, :math:`\mathbf v_k \sim N(0, R)`, has the error
    :math:`\mathbf e_k = A_k(F\mathbf e_{k-1} - \mathbf d_k) + K_k\mathbf v_k` with
    :math:`\mathbf d_k = \mathbf x_k - F\mathbf x_{k-1}` (the part of the path the model does not predict:
    zero on a straight leg). So its mean :math:`\mathbf b_k = A_k(F\mathbf b_{k-1} - \mathbf d_k)` and its
    covariance :math:`C_k = A_kFC_{k-1}F^\top A_k^\top + K_kRK_k^\top`: the RMSE over infinitely many
    runs, without Monte Carlo. The filter's own :math:`P_k` equals :math:`C_k` only for targets that
    follow its model; on a path smoother than its :math:`Q` it is larger.

    Parameters
    ----------
    gains : GainSequence
        The filter's gains (:func:`gain_sequence`), shape (K, n, m).
    truth : array_like, shape (K, n)
        True states.
    R : array_like, shape (m, m)
        Covariance of the measurement noise that is actually added (positive definite).
    mean0, cov0 : array_like, shapes (n,) and (n, n)
        Mean and covariance of the initial error (e.g. a zero initial velocity: mean ``-v``; a first
        measurement as initial position: covariance ``R`` there). ``cov0`` positive semidefinite.

    Returns
    -------
    ErrorMoments
        ``mean`` (K, n) and ``cov`` (K, n, n): the error's exact mean and covariance at each step.

    Raises
    ------
    ValueError
        Arrays of the wrong shape or not finite, covariances not valid; the steps of ``gains`` (with the sizes
        ``n`` and ``m``) beyond the work budget (``fusion._limits.MAX_WORK``, ~10 CPU-s), named ``gains``.

    References
    ----------
    * Bar-Shalom, Y., Li, X. R., & Kirubarajan, T. (2001). *Estimation with Applications to
      Tracking and Navigation*, §5.2 (the filter's error recursion). Wiley.
    """
    instance_of(gains, GainSequence, "gains")
    F, H = gains.F, gains.H
    n, m = F.shape[0], H.shape[0]
    K = gains.K.shape[0]
    # rule 17 (fuzz 37a C3): a Python step per step of gains
    _steps_work(K, 1, n, m, 2 * LOOP_STEP, "gains (its steps K and sizes)", ERROR_MOMENTS_CUBE, ERROR_MOMENTS_M_CUBE,
                matrix=ERROR_MOMENTS_MATRIX)
    X = as_array(truth, "truth", shape=(K, n))
    R = as_covariance(R, dim=m, name="R")
    b = as_array(mean0, "mean0", shape=(n,)).copy()
    C = as_semidefinite(cov0, dim=n, name="cov0").copy()
    means, covs = np.empty((K, n)), np.empty((K, n, n))
    means[0], covs[0] = b, C
    eye = np.eye(n)
    for k in range(1, K):
        G = gains.K[k]
        A = eye - G @ H
        AF = A @ F
        b = AF @ b - A @ (X[k] - F @ X[k - 1])
        C = AF @ C @ AF.T + G @ R @ G.T
        means[k], covs[k] = b, 0.5 * (C + C.T)
    return ErrorMoments(mean=means, cov=covs)


def rmse_per_step(estimates: ArrayLike, truth: ArrayLike) -> FloatArray:
    """Root-mean-square error over runs at each step, per state component.

    Parameters
    ----------
    estimates : array_like, shape (runs, K, d)
    truth : array_like, shape (K, d) or (runs, K, d)
        One true path for every run, or one per run (targets that follow a random model).

    Returns
    -------
    ndarray, shape (K, d)
        Entry (k, j): the RMS over runs of the error of component j at step k.

    Raises
    ------
    ValueError
        Non-finite input, or ``truth`` of neither shape.
    """
    est = as_array(estimates, "estimates", ndim=3)
    tr = as_array(truth, "truth", ndim=(2, 3))
    if tr.shape not in (est.shape[1:], est.shape):
        raise ValueError(f"truth must be {est.shape[1:]} or {est.shape} to match estimates (runs, K, d), "
                         f"got {tr.shape}")
    e = est - (tr if tr.ndim == 3 else tr[None])
    return np.sqrt(np.mean(e**2, axis=0))


def nees(errors: ArrayLike, covariances: ArrayLike) -> FloatArray:
    r"""Normalised estimation error squared :math:`e^\top P^{-1} e` for every estimate.

    Its mean over runs and steps is the state dimension for a consistent filter (smaller for a
    conservative one, larger for an overconfident one).

    Parameters
    ----------
    errors : array_like, shape (..., d)
        Estimate minus truth.
    covariances : array_like, shape (..., d, d)
        The reported covariances, broadcastable against ``errors`` (e.g. (K, d, d) shared by
        all runs of (runs, K, d) errors); symmetric positive definite.

    Returns
    -------
    ndarray, shape of ``errors`` without the last axis (after broadcasting)
        eᵀP⁻¹e of each estimate: χ² with d degrees of freedom (mean d) for a consistent estimator.

    Raises
    ------
    ValueError
        Non-finite input, mismatched shapes, covariances not symmetric positive definite, or their broadcast
        beyond the memory or work budget (``20 + 3 d**2 + 0.008 d**3`` units a matrix of the broadcast).
    """
    # rules 9 and 17 before any entry is read (fuzz 57b C4: two 256 MB arrays whose broadcast is refused were read
    # first, 2.3 CPU-s): each argument's size, then their broadcast from the arrays' shapes, read without converting
    input_size(errors, "errors")
    input_size(covariances, "covariances")
    _nees_shapes_budget(_given_shape(errors), _given_shape(covariances))
    e = as_array(errors, "errors")
    P = as_array(covariances, "covariances", subnormal=True)  # computed covariances: subnormal entries harmless
    if P.ndim >= 2 and P.shape[-1] == P.shape[-2]:
        _covariance_magnitude(P, "covariances")  # the diagonal: no variance that underflows when divided by
    if e.ndim < 1 or P.ndim < 2 or P.shape[-2:] != (e.shape[-1], e.shape[-1]):
        raise ValueError(f"errors (..., d) and covariances (..., d, d) do not match: {e.shape}, {P.shape}")
    try:
        batch = np.broadcast_shapes(e.shape[:-1], P.shape[:-2])
    except ValueError:
        raise ValueError(f"errors {e.shape} and covariances {P.shape} do not broadcast") from None
    d = e.shape[-1]
    # rules 9 and 17 (fuzz 57b C4), before the covariances' own O(d**3) checks: the result, one number per matrix of
    # the broadcast, and the work, 20 + 3 d**2 + 0.008 d**3 units a matrix (its symmetry check, Cholesky factor and
    # LU solve), measured (time.process_time, OPENBLAS_NUM_THREADS=1, shared machine; one covariance per error):
    # 87 ns a matrix at d = 1, 296 ns at d = 2, 671 ns at d = 4, 2.0 us at d = 8, 33 us at d = 32, 0.49 ms at d = 128,
    # 16.5 ms at d = 512, 0.24 s at d = 1,500 (a d = 5,792 matrix ran 14 CPU-s unchecked).
    _nees_budget(batch, d)
    if asymmetric(P):   # the covariance readers' rule (each matrix's scale)
        raise ValueError("covariances must be symmetric")
    try:
        L = np.linalg.cholesky(P)
    except np.linalg.LinAlgError:
        raise ValueError("covariances must be positive definite") from None
    L, eb = np.broadcast_arrays(L, e[..., None])
    # solved by blocks of the broadcast (fuzz 57b C4: numpy copied the broadcast factors whole, 16 GiB for errors
    # (64, 8192, 64) against covariances (8192, 64, 64)): each block's solve is the whole one's, so the same bits
    blocks = _blocks(batch, max(1, _NEES_BLOCK // (d * d)))
    if len(blocks) == 1:  # the whole broadcast at once (a scalar for one error)
        return np.sum(np.linalg.solve(L, eb)[..., 0] ** 2, axis=-1)
    out = np.empty(batch)
    for block in blocks:
        y = np.linalg.solve(L[block], eb[block])[..., 0]
        out[block] = np.sum(y**2, axis=-1)
    return out


def _nees_shapes_budget(es: tuple[int, ...] | None, ps: tuple[int, ...] | None) -> None:
    """:func:`_nees_budget` of the arguments' shapes ``es`` and ``ps`` before their conversion, where both are arrays
    (None: no shape without converting) of matching, broadcasting shapes; any other shape is left to the checks after
    the conversion, which name it."""
    if es is None or ps is None or len(es) < 1 or len(ps) < 2 or tuple(ps[-2:]) != (es[-1], es[-1]):
        return
    try:
        batch = np.broadcast_shapes(tuple(es[:-1]), tuple(ps[:-2]))
    except ValueError:
        return
    _nees_budget(batch, int(es[-1]))


def _nees_budget(batch: tuple[int, ...], d: int) -> int:
    """Refuse :func:`nees` of a broadcast ``batch`` of ``d x d`` matrices beyond the memory or work budget (the
    measurements at its call); the units of work."""
    allocation(batch, "errors and covariances (their broadcast shape)")
    return work((math.prod(batch),), "errors and covariances (their broadcast matrices)",
                weight=20 + 3 * d * d + math.ceil(0.008 * d**3))


#: Entries of the broadcast covariance factors :func:`nees` solves at once (32 MiB of float64).
_NEES_BLOCK = 2**22


def _blocks(shape: tuple[int, ...], size: int) -> list[tuple[object, ...]]:
    """Index tuples covering an array of ``shape`` in C order by blocks of at most ``size`` entries (and at least half
    that, but for each block ending an axis): whole trailing axes and a slice of the next one."""
    if math.prod(shape) <= size:
        return [(Ellipsis,)]
    a = len(shape) - 1
    while math.prod(shape[a:]) <= size:
        a -= 1
    inner = math.prod(shape[a + 1:])
    step = max(1, size // inner)
    return [(*outer, slice(s, s + step)) for outer in np.ndindex(*shape[:a]) for s in range(0, shape[a], step)]


# ---------------------------------------------------------------- scalar fast path (decoupled axes)
#
# A constant-velocity filter on independent axes (F, Q, P0 block diagonal in 2 x 2 blocks, H reading the
# first component of each block, R diagonal) never couples its axes: each entry of every product of the
# recursion above has at most two non-zero terms, and of two, either both are products by an entry of F
# (0, 1 or -1: exact) or the later one in the sum is a product by 1 (from I - KH); and the inverse of the
# diagonal HPH' + R holds the reciprocals of its entries. A BLAS that accumulates a product's terms in
# order (with or without fused multiply-adds) then rounds each entry once, exactly as the same sum written
# with Python floats does. So a recursion per axis on Python floats gives the same bits as the matrix
# recursion at a fifth of its cost (a single run's cost is per-step overhead, not arithmetic). Whether this
# process's BLAS orders its sums so is checked once (``_scalar_path_ok``); if not, the matrix recursion is used.

_UNIT = (0.0, 1.0, -1.0)  # transition entries whose products are exact


def _decoupled_axes(F: FloatArray, H: FloatArray, *covs: FloatArray) -> int:
    """The number of independent 2-D axes (position, rate) of the model, or 0 when the scalar path does not apply.

    Applies when ``F`` (entries 0, 1 or -1 only) and every matrix of ``covs`` are block diagonal in
    2 x 2 blocks and ``H`` reads component ``2i`` in row ``i`` (so ``R`` must be diagonal: see callers).
    Checked entry by entry on Python lists (the matrices are small; numpy's per-call cost would dominate).
    """
    n, m = F.shape[0], H.shape[0]
    if n != 2 * m:
        return 0
    for i, row in enumerate(H.tolist()):
        for j, v in enumerate(row):
            if v != (1.0 if j == 2 * i else 0.0):
                return 0
    for A in (F, *covs):
        for i, row in enumerate(A.tolist()):
            for j, v in enumerate(row):
                if v != 0.0 and i // 2 != j // 2:
                    return 0
    for i, row in enumerate(F.tolist()):
        for j in range(i - i % 2, i - i % 2 + 2):
            if row[j] not in _UNIT:
                return 0
    return m


def _axis_gains(f: list[float], q: list[float], r: float, p: list[float], n_steps: int
                ) -> tuple[list[float], list[float]]:
    """One axis of :func:`gain_sequence` on Python floats, entry by entry as the matrix products round them.

    ``f``, ``q``, ``p``: the axis's 2 x 2 blocks of F, Q and P0, row-major; ``r`` its measurement variance.
    Returns the gains ``k0, k1`` (2 floats a step) and covariances (4 floats a step, row-major) of steps
    1.. up to the step where the covariance first repeats itself exactly (every later step repeats it too).
    """
    f00, f01, f10, f11 = f
    q00, q01, q10, q11 = q
    a, b, c, d = p
    gains: list[float] = []
    covs: list[float] = []
    for _ in range(1, n_steps):
        # predict: F P F' + Q (every product by an entry of F is exact)
        u00, u01 = f00 * a + f01 * c, f00 * b + f01 * d
        u10, u11 = f10 * a + f11 * c, f10 * b + f11 * d
        e00 = (u00 * f00 + u01 * f01) + q00
        e01 = (u00 * f10 + u01 * f11) + q01
        e10 = (u10 * f00 + u11 * f01) + q10
        e11 = (u10 * f10 + u11 * f11) + q11
        # gain: P H' (H P H' + R)^-1, with the inverse of a diagonal matrix
        si = 1.0 / (e00 + r)
        k0, k1 = e00 * si, e10 * si
        # Joseph form (I - KH) P (I - KH)' + K R K', I - KH = [[g, 0], [-k1, 1]]
        g = 1.0 - k0
        A00, A01 = g * e00, g * e01
        A10, A11 = e10 - k1 * e00, e11 - k1 * e01
        kr0, kr1 = k0 * r, k1 * r
        na = A00 * g + kr0 * k0
        nb = (A01 - A00 * k1) + kr0 * k1
        nc = A10 * g + kr1 * k0
        nd = (A11 - A10 * k1) + kr1 * k1
        gains += (k0, k1)
        covs += (na, nb, nc, nd)
        if na == a and nb == b and nc == c and nd == d:
            break  # the fixed point: every later step gives these same bits
        a, b, c, d = na, nb, nc, nd
    return gains, covs


def _axis_states(f: list[float], k0: list[float], k1: list[float], z: list[float],
                 x0: float, x1: float) -> tuple[list[float], list[float]]:
    """One axis of one run of :func:`filter_runs` on Python floats (the same roundings as its matrix products).

    ``k0``, ``k1``: the axis's gains at every step (index 0 unused), ``z`` its readings, ``(x0, x1)`` its
    initial (position, rate). Returns the filtered positions and rates of every step.
    """
    f00, f01, f10, f11 = f
    pos, rate = [x0], [x1]
    for g0, g1, zk in zip(k0[1:], k1[1:], z[1:]):
        p, v = f00 * x0 + f01 * x1, f10 * x0 + f11 * x1  # x = F x (exact products)
        y = zk - p
        x0, x1 = p + g0 * y, v + g1 * y
        pos.append(x0)
        rate.append(x1)
    return pos, rate


def _gains_axes(F: FloatArray, Q: FloatArray, R: FloatArray, P0: FloatArray, n_steps: int
                ) -> tuple[FloatArray, FloatArray]:
    """:func:`_gains_matrices` for a model of independent axes (:func:`_decoupled_axes`), one axis at a time."""
    n, m = F.shape[0], R.shape[0]
    Ks = np.zeros((n_steps, n, m))
    Ps = np.zeros((n_steps, n, n))
    Ps[0] = P0
    if n_steps == 1:
        return Ks, Ps
    Fl, Ql, Pl = F.tolist(), Q.tolist(), P0.tolist()
    for i in range(m):
        j = 2 * i
        block = lambda A: [A[j][j], A[j][j + 1], A[j + 1][j], A[j + 1][j + 1]]  # noqa: E731
        gains, covs = _axis_gains(block(Fl), block(Ql), float(R[i, i]), block(Pl), n_steps)
        rest = n_steps - 1 - len(gains) // 2  # steps after the fixed point repeat its gain and covariance
        Ks[1:, j:j + 2, i] = np.reshape(gains + gains[-2:] * rest, (n_steps - 1, 2))
        Ps[1:, j:j + 2, j:j + 2] = np.reshape(covs + covs[-4:] * rest, (n_steps - 1, 2, 2))
    return Ks, Ps


def _states_axes(z: FloatArray, gains: GainSequence, x: FloatArray) -> FloatArray:
    """:func:`filter_runs` for gains of independent axes, one run and one axis at a time on Python floats."""
    K, n, m = gains.K.shape
    out = np.empty((z.shape[0], K, n))
    for i in range(m):
        s = slice(2 * i, 2 * i + 2)
        f = gains.F[s, s].ravel().tolist()
        k0, k1 = gains.K[:, 2 * i, i].tolist(), gains.K[:, 2 * i + 1, i].tolist()
        for r in range(z.shape[0]):
            pos, rate = _axis_states(f, k0, k1, z[r, :, i].tolist(), float(x[r, 2 * i]), float(x[r, 2 * i + 1]))
            out[r, :, 2 * i], out[r, :, 2 * i + 1] = pos, rate
    return out


_PROBE: list[bool] = []


def _scalar_path_ok() -> bool:
    """Whether this process's BLAS rounds the recursion's products as the scalar path does (checked once).

    The scalar path (:func:`_gains_axes`, :func:`_states_axes`) and the matrix recursion are run on a small
    problem of two independent axes whose products have an inexact first term and an exact second one; the
    scalar path is used only if the two agree bit for bit.
    """
    if not _PROBE:
        F = np.kron(np.eye(2), [[1.0, 1.0], [0.0, 1.0]])
        Q = np.kron(np.diag([0.3, 7.0]), [[1.0 / 3.0, 0.5], [0.5, 1.0]])
        R, P0 = np.diag([2.7, 0.11]), np.kron(np.diag([1.3, 50.0]), [[1.0, 0.1], [0.1, 0.7]])
        H = np.array([[1.0, 0.0, 0.0, 0.0], [0.0, 0.0, 1.0, 0.0]])
        Ka, Pa = _gains_axes(F, Q, R, P0, 12)
        Km, Pm = _gains_matrices(F, H, Q, np.broadcast_to(R, (12, 2, 2)), P0, 12)
        g = trusted(GainSequence, K=Km, P=Pm, F=F, H=H)
        z = np.sin(np.arange(24.0)).reshape(1, 12, 2) * 3.7
        x = np.array([[0.3, -1.1, 2.9, 0.01]])
        same = (np.array_equal(Ka, Km) and np.array_equal(Pa, Pm)
                and np.array_equal(_states_axes(z, g, x), _states_matrices(z, g, x)))
        _PROBE.append(bool(same))
    return _PROBE[0]
