"""The designed scenario of chapter 06 (:mod:`fusion.scenarios.range_bearing`): its parameters, methods and records.

:class:`RangeBearingScenario` (the parameters), :class:`SimulatedTarget` and :func:`simulate_target` (one run's
truth and readings), :class:`TrackingRun` (what one run records) and the methods compared (:data:`METHODS`,
:func:`method_keys`). Re-exported by :mod:`fusion.scenarios.range_bearing`, where they are documented.
"""

from __future__ import annotations

from collections.abc import Mapping

from dataclasses import dataclass, field

import numpy as np

from fusion._public import resolve_annotations
from fusion.estimates.chernoff import FusionTimings
from fusion._validation import (_numeric, FloatArray, as_array, as_rng, count, instance_of, one_of, positive_scalar,
                                scalar, std_scalar)
from fusion._validation import count_ceiling, flag
from fusion._validation import store_read
from fusion._results import ResultSpec, array, instance, keyed, number, trusted, validated_post_init
from fusion.filtering.particles import ncv_model, range_bearing
from fusion._shown import shown

__all__ = ["GUARD_STAGES", "READING_METHODS", "METHODS", "RangeBearingScenario", "TrackingRun", "TrackingTimings", "SimulatedTarget",
           "simulate_target", "method_keys"]

#: Tempering steps of the collapse guard (``RangeBearingScenario.guard``).
GUARD_STAGES = 10

#: Methods compared in the scenario, in table order (display labels: :data:`fusion.book.style.METHOD_LABELS`).
METHODS: tuple[str, ...] = (
    "local1", "local2", "local3", "mean_of_local_means", "naive_product", "ci_gaussian", "ci_det", "ci_trace",
    "first_order_uniform", "chernoff_uniform", "chernoff_pso", "chernoff_slsqp", "chernoff_redraw", "chernoff_prev",
    "chernoff_first_order_start", "chernoff_first_order", "chernoff_literal", "centralised_pf",
)


@dataclass(frozen=True)
class RangeBearingScenario:
    """Parameters of the designed scenario (the patent gives none).

    Units: metres, seconds, radians (``sigma_theta``). State :math:`[x, \\dot x, y, \\dot y]`.

    Attributes
    ----------
    sensors : tuple of (float, float)
        Sensor positions (m); one particle filter (node) per sensor. Any (N, 2) array-like is accepted and stored
        as a tuple of tuples of floats (as are ``x0`` and ``p0_std``): the frozen scenario holds no alias of the
        caller's list or array, and hashes.
    sigma_r : float
        Range noise standard deviation (m).
    sigma_theta : float
        Bearing noise standard deviation (rad; 2 degrees by default).
    T : float
        Frame period (s).
    q : float
        Acceleration power spectral density of the NCV model (m²/s³), see
        :func:`fusion.filtering.particles.ncv_model`.
    x0 : (float, float, float, float)
        True initial state (m, m/s).
    p0_std : (float, float, float, float)
        Prior standard deviations of the state; ``P0`` is their squared diagonal.
    frames : int
        Number of frames K.
    n_particles : int
        Particles per local filter.
    n_components : int
        Gaussian-mixture components fitted by EM to each local posterior.
    n_samples : int
        Importance samples of the Chernoff fusion (patent step E).
    n_central : int
        Particles of the centralised reference filter.
    em_iterations : int
        EM iteration limit.
    regularised : bool
        Jitter resampled particles (:func:`fusion.filtering.particles.regularise`).
    n_initial : int
        Particles each node draws from the prior for its first update (0: ``n_particles``). When
        larger than ``n_particles``, the node resamples (and jitters) them down to ``n_particles``
        right after the first weighting, before its mixture fit: a guard against the collapse of
        the first update, whose likelihood is much narrower than the prior (chapter 06).
    guard : float
        Collapse guard of the local filters (0: none). When a node's effective sample size after
        weighting falls below ``guard`` times its particle count, the node redoes that update by
        progressive correction (Oudjane & Musso 2000): the likelihood is applied in
        :data:`GUARD_STAGES` equal tempering steps, with systematic resampling and regularisation
        between them. A run in which no node falls below the threshold is identical to the
        unguarded one (the guard draws nothing otherwise).
    central_guard : float
        The same guard for the centralised filter (0: none), with its own generator and every sensor's
        likelihood; recorded in ``TrackingRun.guarded`` as node -1.
    variants : bool
        Compute the variants ``chernoff_slsqp``, ``chernoff_redraw`` and ``chernoff_prev`` (False:
        their records are NaN, and the run is about a third cheaper).
    prev_optimiser : {"pso", "newton"}
        Step G of the variant ``chernoff_prev`` (ε⁽⁰⁾ = the previous frame's ε*): the swarm (default), or the
        exact minimum of :math:`\\hat J` by the projected Newton method, which the swarm reaches within its
        sampling error (chapter 06, record ``chf-pso``) at a fraction of the cost. The variant draws from the
        fusion's random stream after the main fusion, so this choice (like ``variants``) moves the samples of every
        fusion method from the second frame on.
    readings : bool
        Also run two readings of steps D and F (chapter 06; off by default: not recorded):
        ``chernoff_first_order_start``, the initial exponents of step D chosen by minimising the first-order normaliser
        :math:`Z_{\\rm FO}` (which needs no exponents: no circularity), then steps E-I from its own random
        stream, step G by the exact minimum of :math:`\\hat J` (projected Newton: the swarm's optimum within
        its sampling error, record ``chf-pso``, at a fraction of its cost); ``chernoff_first_order``, the same fusion at those exponents without steps F-G; and,
        on the samples of the main fusion, the equal-KL rule (``eps["equal_kl"]``, NaN where it has no
        solution in the simplex) and the same rule applied to the first-order mixture :math:`g` of step D at the
        rule's own exponents (``eps["equal_kl_g"]``, ``fusion.scenarios.range_bearing_batch._equal_kl_on_mixture``,
        deterministic); and the patent's stopping rule G6 as worded, ``chernoff_literal``: the
        main swarm is followed to its iteration limit (on a copy of its generator) and its best point
        when the positions have converged (every particle within ``literal_xtol`` of the best) is used on
        the same samples (``swarm_trace`` records the best fitness and the spread after every iteration,
        for any other tolerance). The other methods' results do not change.
    literal_xtol : float
        Position tolerance of the literal stopping rule (``readings``).
    """

    sensors: tuple[tuple[float, float], ...] = ((0.0, 0.0), (2000.0, 0.0), (1000.0, 2000.0))
    sigma_r: float = 10.0
    sigma_theta: float = float(np.deg2rad(2.0))
    T: float = 1.0
    q: float = 0.5
    x0: tuple[float, float, float, float] = (800.0, 15.0, 600.0, 10.0)
    p0_std: tuple[float, float, float, float] = (30.0, 3.0, 30.0, 3.0)
    frames: int = 30
    n_particles: int = 2000
    n_components: int = 3
    n_samples: int = 2000
    n_central: int = 10000
    em_iterations: int = 20
    regularised: bool = True
    n_initial: int = 0
    guard: float = 0.0
    variants: bool = True
    readings: bool = False
    central_guard: float = 0.0
    prev_optimiser: str = "pso"
    literal_xtol: float = 1e-3

    def __post_init__(self) -> None:
        S = _numeric(self.sensors, "sensors")
        if S.ndim != 2 or S.shape[0] < 1 or S.shape[1] != 2:
            raise ValueError(f"sensors must be N >= 1 positions (x, y), shape (N, 2), got {S.shape}")
        if S.shape[0] > count_ceiling("sensors"):  # rule 9 by its length, before the rows are checked and stored as
            # tuples (fix72e: 2 million sensors were converted in 2.1 CPU-s, about 17 at the input budget, and accepted)
            raise ValueError(f"sensors holds {S.shape[0]:,} sensors, beyond the ceiling of a count of dimension "
                             f"({count_ceiling('sensors'):,}; fusion._validation.COUNT_CEILINGS)")
        S = as_array(S, "sensors", shape=(None, 2))   # finite, and the shared magnitude rule (1e150, no subnormal)
        # frozen: store what was checked, as tuples of floats (hashable, and no alias of the caller's list or array)
        object.__setattr__(self, "sensors", tuple(tuple(row) for row in S.tolist()))
        for name in ("sigma_r", "sigma_theta"):
            store_read(self, name, std_scalar(getattr(self, name), name))
        for name in ("T", "q"):
            store_read(self, name, positive_scalar(getattr(self, name), name))
        x0 = as_array(self.x0, "x0", shape=(4,))
        p0 = as_array(self.p0_std, "p0_std", shape=(4,))
        if np.any(p0 <= 0):
            raise ValueError("p0_std must be positive")
        object.__setattr__(self, "x0", tuple(x0.tolist()))
        object.__setattr__(self, "p0_std", tuple(p0.tolist()))
        for name, least in (("frames", 1), ("n_particles", 2), ("n_components", 1), ("n_samples", 2),
                            ("n_central", 2), ("em_iterations", 1)):
            store_read(self, name, count(getattr(self, name), name, minimum=least))
        store_read(self, "n_initial", count(self.n_initial, "n_initial", minimum=0))
        flag(self.regularised, "regularised")
        flag(self.variants, "variants")
        flag(self.readings, "readings")
        store_read(self, "prev_optimiser", one_of(self.prev_optimiser, ("pso", "newton"), "prev_optimiser"))
        store_read(self, "literal_xtol", positive_scalar(self.literal_xtol, "literal_xtol"))
        for name in ("guard", "central_guard"):
            g = _numeric(getattr(self, name), name)
            if g.ndim != 0 or not np.isfinite(g) or not 0.0 <= float(g) < 1.0:
                raise ValueError(f"{name} must be a fraction in [0, 1), got {shown(getattr(self, name))}")
            if float(g) != 0.0:
                scalar(float(g), name, 0.0, 1.0, hi_open=True)  # the shared magnitude rule (no subnormal)
            store_read(self, name, float(g))
        if self.n_components > self.n_particles:
            raise ValueError("n_components must not exceed n_particles")

    @property
    def sensor_array(self) -> FloatArray:
        return np.asarray(self.sensors, dtype=float)

    @property
    def P0(self) -> FloatArray:
        return np.diag(np.asarray(self.p0_std, dtype=float) ** 2)


@dataclass(frozen=True)
class TrackingTimings:
    """Seconds per stage of one run of the tracking study (:func:`run_tracking`, :func:`run_tracking_batch`).

    Wall-clock times: not deterministic, for benchmarks only. A batch's times are shared equally by its runs; a stage
    the run did not go through takes 0.

    Attributes
    ----------
    setup : float
        Drawing the targets and readings, allocating the outputs.
    particle_filters : float
        Step B, the local particle filters.
    em : float
        Step C, the weighted EM mixtures.
    gaussian_baselines : float
        The naive product and the CIs of moment-matched Gaussians.
    fusion : fusion.estimates.chernoff.FusionTimings
        Steps D-I of the first fusion, by stage.
    literal_stop : float
        G6 as worded, read from the traced swarm (``readings``).
    variants : float
        The fusion's variants (ε⁽⁰⁾ = previous ε*, the readings of D and F) and every node's own fusion.
    centralised_pf : float
        The centralised particle filter and the local filters' resampling.
    """

    setup: float = 0.0
    particle_filters: float = 0.0
    em: float = 0.0
    gaussian_baselines: float = 0.0
    fusion: FusionTimings = field(default_factory=FusionTimings)
    literal_stop: float = 0.0
    variants: float = 0.0
    centralised_pf: float = 0.0

    __result_spec__ = ResultSpec(
        {"setup": number(), "particle_filters": number(), "em": number(), "gaussian_baselines": number(),
         "fusion": instance(FusionTimings), "literal_stop": number(), "variants": number(), "centralised_pf": number()})
    __post_init__ = validated_post_init


def _covariances_of_estimates(values: dict, cls: str) -> None:
    """Every method with a covariance has an estimate (its NEES needs both)."""
    extra = sorted(set(values["covariances"]) - set(values["estimates"]))
    if extra:
        raise ValueError(f"{cls}.covariances has methods without an estimate in {cls}.estimates: {extra}")


def _component_counts(values: dict, cls: str) -> None:
    """Each frame fuses a whole number of mixture components, at least one."""
    n = values["n_fused_components"]
    if not np.all((n >= 1) & (n == np.round(n))):
        raise ValueError(f"{cls}.n_fused_components must hold whole numbers >= 1 (components fused per frame)")


@dataclass(frozen=True)
class TrackingRun:
    """Everything one Monte-Carlo run records (arrays indexed by frame first).

    Frozen; ``truth``, ``estimates`` and ``covariances`` (what :func:`position_sq_errors` and :func:`nees_per_frame`
    read), ``swarm_history``, ``gm_loglik``, ``gm1_loglik`` and ``n_fused_components`` are validated when built
    (``fusion._results``): finite, the same frames K throughout, (K, 4) states, symmetric positive-semidefinite
    (K, 4, 4) covariances of methods that have an estimate, (K, N) log-likelihoods of the same N nodes, whole
    numbers of components >= 1, stored read-only. The other records may hold NaN where a method did not run (a
    variant switched off).

    Attributes
    ----------
    truth : (K, 4)
    estimates : mapping key -> (K, 4); keys of :data:`METHODS`
    covariances : mapping key -> (K, 4, 4); every method except ``mean_of_local_means``
    eps : mapping {"pso", "slsqp", "prev", "ci_gaussian", "ci_det", "ci_trace", "first_order", "equal_kl", "equal_kl_g", "literal"} -> (K, N)
    ess : mapping {"pso", "uniform", "redraw", "prev", "first_order_start", "centralised_pf"} -> (K,);
        ``"local"`` -> (K, N) (before resampling)
    objective : mapping {"pso", "slsqp", "literal"} -> (K,)
    swarm_history : (K, n) best fitness after each swarm iteration (padded with the final
        value after an early stop: the swarm stopped after iteration ``evaluations["pso"] / 20 - 1``)
    evaluations : mapping {"pso", "slsqp", "literal"} -> (K,)
    gm_loglik : (K, N) weighted log-likelihood of each node's particles under its mixture
    gm1_loglik : (K, N) the same for a single moment-matched Gaussian
    n_fused_components : (K,)
    node_estimates : (K, N, 4) or None, with ``all_nodes=True``: every node's own fusion
    timings : TrackingTimings
        Seconds per stage (not deterministic; benchmarks only).
    guarded : tuple of (frame, node), 0-based: the updates redone by the collapse guard
        (``RangeBearingScenario.guard``); node -1 is the centralised filter
    swarm_trace : mapping {"fitness", "spread"} -> (K, iterations + 1), or empty
        With ``readings``: the main swarm followed to its iteration limit, best fitness and spread of its
        positions (largest coordinate difference from the best point) after every iteration
        (:class:`fusion.optimise.result.SwarmTrace`)
    scenario : RangeBearingScenario or None
        The scenario the run was computed with (set by the package's runs; None for a run built by hand): the
        chapter helpers compare it with the scenario they are given (``fusion.scenarios.range_bearing._check_runs``).
    """

    truth: FloatArray
    estimates: Mapping[str, FloatArray]
    covariances: Mapping[str, FloatArray]
    eps: Mapping[str, FloatArray]
    ess: Mapping[str, FloatArray]
    objective: Mapping[str, FloatArray]
    swarm_history: FloatArray
    evaluations: Mapping[str, FloatArray]
    gm_loglik: FloatArray
    gm1_loglik: FloatArray
    n_fused_components: FloatArray
    node_estimates: FloatArray | None
    timings: TrackingTimings = field(default_factory=lambda: TrackingTimings())
    guarded: tuple[tuple[int, int], ...] = ()
    swarm_trace: Mapping[str, FloatArray] = field(default_factory=dict)
    scenario: RangeBearingScenario | None = None

    __result_spec__ = ResultSpec(
        {"truth": array("K", 4), "estimates": keyed("K", 4), "covariances": keyed("K", 4, 4, covariance=True),
         "swarm_history": array("K", "iterations"), "gm_loglik": array("K", "N"), "gm1_loglik": array("K", "N"),
         "n_fused_components": array("K")},
        relations=(_covariances_of_estimates, _component_counts))
    __post_init__ = validated_post_init


def _wrapped_bearings(values: dict, cls: str) -> None:
    """Every bearing reading is wrapped to (-pi, pi] (what the filters' likelihoods assume)."""
    bearing = values["z"][..., 1]
    if not np.all((bearing > -np.pi) & (bearing <= np.pi)):
        bad = float(bearing[~((bearing > -np.pi) & (bearing <= np.pi))][0])
        raise ValueError(f"{cls}.z: bearings (z[..., 1]) must lie in (-pi, pi], got {shown(bad)}")


@dataclass(frozen=True)
class SimulatedTarget:
    """One simulated target: true states, readings and the shared prior mean.

    Arrays are read-only.

    Attributes
    ----------
    truth : ndarray, shape (K, 4)
        True states (m, m/s).
    z : ndarray, shape (K, N, 2)
        Range (m) and bearing (rad, in (-pi, pi]) of each sensor at each frame.
    m0 : ndarray, shape (4,)
        Prior mean shared by all filters.
    """

    truth: FloatArray
    z: FloatArray
    m0: FloatArray

    __result_spec__ = ResultSpec({"truth": array("K", 4), "z": array("K", "N", 2), "m0": array(4)},
                                 relations=(_wrapped_bearings,))
    __post_init__ = validated_post_init


def refuse_on_sensor(sc: RangeBearingScenario, positions: FloatArray, name: str, what: str, why: str) -> None:
    """The scenario's one rule for a position on a sensor (fuzz 28a C5): at range 0 the bearing and its Jacobian are
    undefined, so a position (..., 2) that coincides with a sensor is refused, naming ``name`` and saying ``what``
    coincides with which sensor and ``why`` that is refused. Used by every entry that evaluates the measurement
    function at given or computed positions: ``posterior_crb`` (its truths), ``linearised_errors`` (the nominal
    trajectory from ``sc.x0``) and :func:`simulate_target` (the simulated truth of ``run_tracking``,
    ``run_tracking_batch`` and ``monte_carlo``)."""
    P = np.asarray(positions, dtype=float)
    for i, s in enumerate(sc.sensor_array):
        hit = (P[..., 0] == s[0]) & (P[..., 1] == s[1])
        if np.any(hit):
            raise ValueError(f"{name}: {what} coincides with sensor {i + 1} at ({shown(float(s[0]))}, "
                             f"{shown(float(s[1]))}); the bearing and its Jacobian are undefined there, {why}")


def simulate_target(sc: RangeBearingScenario, rng: np.random.Generator) -> SimulatedTarget:
    """Truth, measurements and the shared prior mean of one run.

    The truth starts at ``x0`` and follows the NCV model with process noise; the prior mean
    is :math:`m_0 = x_0 + P_0^{1/2}\\xi`; frame :math:`k = 1..K` is measured by every sensor with
    independent range-bearing noise.

    Parameters
    ----------
    sc : RangeBearingScenario
        The scenario.
    rng : numpy.random.Generator
        Draws the process noise, the prior mean and the measurement noise.

    Returns
    -------
    SimulatedTarget
        ``truth``, ``z`` and ``m0``.
    """
    instance_of(sc, RangeBearingScenario, "sc")
    as_rng(rng)
    model = ncv_model(sc.T, sc.q)
    F, Q = model.F, model.Q
    LQ = np.linalg.cholesky(Q)
    x = np.asarray(sc.x0, dtype=float)
    m0 = x + np.asarray(sc.p0_std) * rng.standard_normal(4)
    truth = np.empty((sc.frames, 4))
    for k in range(sc.frames):
        x = F @ x + LQ @ rng.standard_normal(4)
        truth[k] = x
    refuse_on_sensor(sc, truth[:, [0, 2]], "sc", "the simulated target from sc.x0", "so it has no reading")
    S = sc.sensor_array
    h = np.stack([range_bearing(truth, s) for s in S], axis=1)  # (K, N, 2)
    noise = rng.standard_normal(h.shape) * [sc.sigma_r, sc.sigma_theta]
    z = h + noise
    w = np.angle(np.exp(1j * z[..., 1]))  # in [-pi, pi]: -pi for a bearing within ~1e-16 of -pi (fuzz 27a D5)
    z[..., 1] = np.where(w == -np.pi, np.pi, w)  # (-pi, pi], the range SimulatedTarget's spec states
    # fresh arrays of validated inputs: the private constructor (the spec's check cost 10 % of study_truths)
    return trusted(SimulatedTarget, truth=truth, z=z, m0=m0)


#: Methods computed only with ``RangeBearingScenario.readings``.
READING_METHODS = ("chernoff_first_order_start", "chernoff_first_order", "chernoff_literal")


def method_keys(n_sensors: int, readings: bool = False) -> list[str]:
    """Keys of :attr:`TrackingRun.estimates` for ``n_sensors`` sensors.

    Parameters
    ----------
    n_sensors : int
        Number of sensor nodes, at least one.
    readings : bool
        Include the readings of steps D, F and G6 (:data:`READING_METHODS`, ``RangeBearingScenario.readings``).

    Returns
    -------
    list of str
        One local filter per sensor (``local1`` ...), then the fusion methods and the centralised
        filter, in the order of :data:`METHODS`.
    """
    n_sensors = count(n_sensors, "n_sensors")
    flag(readings, "readings")
    return [f"local{i + 1}" for i in range(n_sensors)] + [k for k in METHODS if not k.startswith("local")
                                                           and (readings or k not in READING_METHODS)]



# the public home of these names is fusion.scenarios.range_bearing (documentation, pickles, the input registry)
for _obj in (RangeBearingScenario, TrackingRun, TrackingTimings, SimulatedTarget, simulate_target, method_keys):
    if isinstance(_obj, type):
        resolve_annotations(_obj)   # their hints resolve under the new name too
    _obj.__module__ = "fusion.scenarios.range_bearing"
del _obj
